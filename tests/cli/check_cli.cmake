# Runs one `ncpost` command line and checks its exit status and output.
# -DCOMMAND="a;b;c" -DEXPECT_EXIT=N [-DSTDIN=file] [-DSTDOUT_MATCH=regex] [-DSTDERR_MATCH=regex]
# [-DSTDOUT_EMPTY=1]
set(args ${COMMAND})
if(STDIN)
  execute_process(COMMAND ${args} INPUT_FILE ${STDIN} RESULT_VARIABLE code
                  OUTPUT_VARIABLE out ERROR_VARIABLE err)
else()
  execute_process(COMMAND ${args} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
endif()
if(NOT code STREQUAL EXPECT_EXIT)
  message(FATAL_ERROR "exit status ${code}, expected ${EXPECT_EXIT}\nstdout:\n${out}\nstderr:\n${err}")
endif()
if(STDOUT_MATCH AND NOT out MATCHES "${STDOUT_MATCH}")
  message(FATAL_ERROR "stdout does not match '${STDOUT_MATCH}':\n${out}")
endif()
if(STDERR_MATCH AND NOT err MATCHES "${STDERR_MATCH}")
  message(FATAL_ERROR "stderr does not match '${STDERR_MATCH}':\n${err}")
endif()
if(STDOUT_EMPTY AND NOT out STREQUAL "")
  message(FATAL_ERROR "stdout should be empty:\n${out}")
endif()
