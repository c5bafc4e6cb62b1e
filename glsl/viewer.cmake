# The windowed viewer's own shaders (viewer/): the display pass and the photon dots. Included by
# glsl/CMakeLists.txt when the viewer is built.
photon_compile_shader(viewer_display_vert viewer_display.vert)
photon_compile_shader(viewer_display_frag viewer_display.frag)
photon_compile_shader(viewer_dots viewer_dots.comp)
