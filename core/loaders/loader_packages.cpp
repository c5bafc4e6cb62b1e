// The loader packages' implementations (tinyobjloader, tinygltf; tinyexr in tinyexr_package.cpp), compiled from the
// headers the Debian packages ship: only in the fuzz build (PHOTON_LOADER_SOURCES), so that
// sanitizers and coverage reach into them. Images are decoded by texture_loader.cpp, not by
// tinygltf; stb_image stays the Debian library (environment_loader.cpp walks the HDR pixel data
// itself before stb_image decodes it).
#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>

#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>
