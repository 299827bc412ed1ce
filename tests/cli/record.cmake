# mpcal record: a simulated session fed at the sensor's pace (sped up) by
# record_pace.py through a pipe, a TCP server on the loopback, and a
# pseudo-terminal pair standing in for a serial port (socat); the live
# screen read through tmux; Ctrl-C in the middle. Each ends by itself when
# the positions are enough, and --calibrate equals calibrate on the file.
foreach(case pipe tcp serial screen interrupt)
  add_test(NAME cli.record_${case}
    COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/record_${case}.sh $<TARGET_FILE:mpcal_cli>
            ${MPCAL_PYTHON} ${CMAKE_CURRENT_BINARY_DIR}/record_${case})
  set_tests_properties(cli.record_${case} PROPERTIES LABELS cli TIMEOUT 120)
endforeach()
