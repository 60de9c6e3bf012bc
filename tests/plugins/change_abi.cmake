# cmake -DHEADERS=framework/api/bvhlab -DOUTPUT=DIR/bvhlab -DCHANGE=field|enum|counter -P tests/plugins/change_abi.cmake:
# copies the plugin API's headers into OUTPUT, changed: `field` adds a field to Ray, `enum` swaps
# the values of KeyType::Int and KeyType::Float: the headers of another ABI, for plugins that
# bvhlab must refuse to load (tests/CMakeLists.txt: changed_abi.so, swapped_enum.so). `counter`
# adds a query counter as counters.h says to: the same ABI, for a plugin that bvhlab must load
# (added_counter.so).
file(REMOVE_RECURSE ${OUTPUT})
file(COPY ${HEADERS}/ DESTINATION ${OUTPUT})

# Replaces `from` by `to` in OUTPUT/header, which must hold it.
function(change header from to)
  file(READ ${OUTPUT}/${header} text)
  string(REPLACE "${from}" "${to}" changed "${text}")
  if(changed STREQUAL text)
    message(FATAL_ERROR "change_abi.cmake: no '${from}' in ${HEADERS}/${header} to change")
  endif()
  file(WRITE ${OUTPUT}/${header} "${changed}")
endfunction()

if(CHANGE STREQUAL "field")
  change(ray.h "    float tmax = kInfinity;\n" "    float tmax = kInfinity;\n    float time = 0.0f;\n")
elseif(CHANGE STREQUAL "enum")
  change(settings.h "    Int,       // with an inclusive range\n    Float,     // with an inclusive range\n"
                    "    Float,     // with an inclusive range\n    Int,       // with an inclusive range\n")
elseif(CHANGE STREQUAL "counter")
  change(counters.h "    uint64_t unused[kQueryCounterSlots - 5] = {};"
                    "    uint64_t boxTests = 0;\n    uint64_t unused[kQueryCounterSlots - 6] = {};")
  change(counters.h "    coneTests += o.coneTests;\n" "    coneTests += o.coneTests;\n    boxTests += o.boxTests;\n")
  change(counters.h "&QueryCounters::coneTests, \"the part of N_IT that tested cones and cylinders\"},\n"
                    "&QueryCounters::coneTests, \"the part of N_IT that tested cones and cylinders\"},\n    {\"n_box\", nullptr, &QueryCounters::boxTests, \"boxes tested\"},\n")
else()
  message(FATAL_ERROR "change_abi.cmake: CHANGE must be field, enum or counter, not '${CHANGE}'")
endif()
