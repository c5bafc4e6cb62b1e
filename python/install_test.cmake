# ctest python_install (cmake -P): the install rule's python component into a fresh prefix, then
# the module imported from there, not from the build tree, and rendering. It runs in the prefix: from
# ctest's working directory (build/python) `python3 -c` would import the built module itself.
#   -DBUILD=<build dir> -DPREFIX=<fresh prefix> -DSITE=<PHOTON_PYTHON_INSTALL_DIR> -DPYTHON=<python3> -DSCENE=<scene>
file(REMOVE_RECURSE ${PREFIX})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD} --prefix ${PREFIX} --component python
                COMMAND_ERROR_IS_FATAL ANY)
set(ENV{PYTHONPATH} ${PREFIX}/${SITE})
execute_process(COMMAND ${PYTHON} -c [=[
import os, sys
import photon
where, scene = sys.argv[1:]
assert os.path.realpath(photon.__file__).startswith(os.path.realpath(where)), photon.__file__
image = photon.render(scene, backend="cpu", width=8, height=6, photons=100, frames=1)
print(photon.__file__, image.shape)
]=] ${PREFIX} ${SCENE} WORKING_DIRECTORY ${PREFIX} COMMAND_ERROR_IS_FATAL ANY)
