# ctest install (cmake -P): the install rule's programs component into a fresh prefix, then the
# installed programs run from there: photon-render renders an installed scene, photon-bench times
# one (issue 57: neither photon-bench, the tools nor the scenes were installed).
#   -DBUILD=<build dir> -DPREFIX=<fresh prefix>
file(REMOVE_RECURSE ${PREFIX})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD} --prefix ${PREFIX} --component programs
                OUTPUT_QUIET COMMAND_ERROR_IS_FATAL ANY)
foreach(file bin/photon-render bin/photon-bench bin/photon-converge bin/photon-make-mesh share/photon/scenes/cornell.json
             share/photon/scenes/bunny.obj)
  if(NOT EXISTS ${PREFIX}/${file})
    message(FATAL_ERROR "the install lacks ${file}")
  endif()
endforeach()
execute_process(COMMAND ${PREFIX}/bin/photon-render ${PREFIX}/share/photon/scenes/caustic.json --backend cpu --width 16
                        --height 12 --photons 500 --frames 1 -q -o ${PREFIX}/caustic.pfm
                WORKING_DIRECTORY ${PREFIX} COMMAND_ERROR_IS_FATAL ANY)
execute_process(COMMAND ${PREFIX}/bin/photon-bench --backends cpu --scenes caustic --scenes-dir ${PREFIX}/share/photon/scenes
                        --resolutions 16x12 --photons 500 --cpu-frames 1 --warmup 1
                WORKING_DIRECTORY ${PREFIX} OUTPUT_VARIABLE table COMMAND_ERROR_IS_FATAL ANY)
if(NOT table MATCHES "caustic")
  message(FATAL_ERROR "photon-bench's table names no caustic scene:\n${table}")
endif()
message(STATUS "installed into ${PREFIX}: programs ran there")
