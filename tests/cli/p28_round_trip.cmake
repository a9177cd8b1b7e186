# P21 → P28 (each binding) → P21 through `ncpost convert` must reproduce the P21 text exactly.
execute_process(COMMAND ${NCPOST} convert --to p21 ${INPUT} OUTPUT_FILE ${WORK}/direct.stp RESULT_VARIABLE r0)
foreach(binding late early)
  execute_process(COMMAND ${NCPOST} convert --to p28 --binding ${binding} ${INPUT}
                  OUTPUT_FILE ${WORK}/${binding}.xml RESULT_VARIABLE r1)
  execute_process(COMMAND ${NCPOST} convert --to p21 ${WORK}/${binding}.xml
                  OUTPUT_FILE ${WORK}/${binding}.stp RESULT_VARIABLE r2)
  if(NOT r0 EQUAL 0 OR NOT r1 EQUAL 0 OR NOT r2 EQUAL 0)
    message(FATAL_ERROR "${binding}: exit statuses ${r0} ${r1} ${r2}")
  endif()
  file(READ ${WORK}/direct.stp direct)
  file(READ ${WORK}/${binding}.stp back)
  if(NOT direct STREQUAL back)
    message(FATAL_ERROR "${binding}: the P21 after the P28 round trip differs")
  endif()
endforeach()
