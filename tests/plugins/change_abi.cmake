# cmake -DHEADERS=framework/api/bvhlab -DOUTPUT=DIR/bvhlab -P tests/plugins/change_abi.cmake:
# copies the plugin API's headers into OUTPUT with a field added to Ray, the headers of another
# ABI, for a plugin that bvhlab must refuse to load (tests/CMakeLists.txt, changed_abi.so).
file(REMOVE_RECURSE ${OUTPUT})
file(COPY ${HEADERS}/ DESTINATION ${OUTPUT})
file(READ ${OUTPUT}/ray.h text)
set(field "    float tmax = kInfinity;\n")
string(REPLACE "${field}" "${field}    float time = 0.0f;\n" changed "${text}")
if(changed STREQUAL text)
  message(FATAL_ERROR "change_abi.cmake: no line '${field}' in ${HEADERS}/ray.h to add a field after")
endif()
file(WRITE ${OUTPUT}/ray.h "${changed}")
