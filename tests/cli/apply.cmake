# mpcal apply: correcting logs, pipes, and every bad calibration file.
set(_calib ${MPCAL_TEST_DATA}/apply_calib.json)
set(_log ${MPCAL_TEST_DATA}/apply_log.csv)
mpcal_cli_test(apply_help EXIT 0 MATCH "mpcal apply calib.json" ARGS apply --help)
mpcal_cli_test(apply_corrects EXIT 0 MATCH "corrected 240 rows .*\\|a\\| at rest 9\\.80"
  ARGS apply ${_calib} ${_log} -o out.csv)
mpcal_cli_test(apply_to_stdout_keeps_columns EXIT 0
  MATCH "^0\\.00,21\\.0,9\\.80[0-9]*,-?0\\.00[0-9e-]*,-?0\\.00[0-9e-]*,OK$"
  ARGS apply ${_calib} ${_log} -o -)
mpcal_cli_test(apply_keeps_header_and_comments EXIT 0 MATCH "^time,temp_C,acc_x,acc_y,acc_z,status$"
  ARGS apply ${_calib} ${_log} -o -)
mpcal_cli_test(apply_out_units_g EXIT 0 MATCH "0\\.00,21\\.0,(1\\.000|0\\.999)[0-9]*,"
  ARGS apply ${_calib} ${_log} -o - --out-units g)
mpcal_cli_test(apply_semicolon_decimal_comma EXIT 0 MATCH "0,5;-?0,[0-9]+;-?0,[0-9]+;[0-9]+,[0-9]+;21,5"
  ARGS apply ${_calib} ${MPCAL_TEST_DATA}/log_semicolon_crlf.csv -o - --columns t=zeit)
mpcal_cli_test(apply_wrong_units_warns EXIT 0 MATCH "mpcal: warning: .*magnitude at rest.*--units mps2"
  ARGS apply ${_calib} ${_log} -o out.csv --units g)
mpcal_cli_test(apply_empty_stdin EXIT 1 MATCH "<stdin>.*empty" ABSENT out.csv
  ARGS apply ${_calib} - -o out.csv)
mpcal_cli_test(apply_both_stdin EXIT 1 MATCH "cannot both be standard input"
  ARGS apply - - -o out.csv)
mpcal_cli_test(apply_refuses_own_input EXIT 1 MATCH "does not overwrite its input"
  ARGS apply ${_calib} ${_log} -o ${_log})
mpcal_cli_test(apply_counts_calibration_on_g_log EXIT 1 MATCH "raw counts.*--units counts" ABSENT out.csv
  ARGS apply ${MPCAL_TEST_DATA}/bad_calib_counts.json ${_log} -o out.csv --units g)
mpcal_cli_test(apply_mps2_calibration_on_counts EXIT 1 MATCH "no scale for counts" ABSENT out.csv
  ARGS apply ${_calib} ${_log} -o out.csv --units counts)
mpcal_cli_test(apply_bad_out_units EXIT 2 MATCH "--out-units" ARGS apply ${_calib} ${_log} -o out.csv --out-units counts)
mpcal_cli_test(apply_missing_output EXIT 2 MATCH "--output" ARGS apply ${_calib} ${_log})
foreach(_case
    "version2|this mpcal reads version 1"
    "missing_bias|missing field 'bias_mps2'"
    "model|unknown model 'twelve-parameter'"
    "scale|'input.mps2_per_unit' = -1 is not a sensor's scale"
    "nan|not valid JSON: parse error at line 4, column"
    "syntax|not valid JSON: .*line 22"
    "type|'gravity_mps2' must be a number, found a string")
  string(REPLACE "|" ";" _parts "${_case}")
  list(GET _parts 0 _name)
  list(GET _parts 1 _regex)
  mpcal_cli_test(apply_bad_calib_${_name} EXIT 1 MATCH "${_regex}" ABSENT out.csv
    ARGS apply ${MPCAL_TEST_DATA}/bad_calib_${_name}.json ${_log} -o out.csv)
endforeach()
mpcal_cli_test(apply_missing_calib EXIT 1 MATCH "cannot read calibration file" ABSENT out.csv
  ARGS apply nowhere.json ${_log} -o out.csv)

# In a pipe: the log from standard input, the corrected log to standard
# output (expect.sh gives commands /dev/null as input, so this one uses sh).
add_test(NAME cli.apply_pipe
  COMMAND sh -c "cat '${_log}' | '$<TARGET_FILE:mpcal_cli>' apply '${_calib}' - -o - | grep -c ',OK$' | grep -qx 240")
set_tests_properties(cli.apply_pipe PROPERTIES LABELS cli)
# With --out-units g the header's unit labels follow (phyphox's
# "(m/s^2)" becomes "(g)"). (Numbers are already the shortest that read
# back: std::to_chars.)
mpcal_cli_test(apply_out_units_relabels_header EXIT 0
  MATCH "^\"Time \\(s\\)\",\"Acceleration x \\(g\\)\",\"Acceleration y \\(g\\)\",\"Acceleration z \\(g\\)\",\"Absolute acceleration \\(m/s\\^2\\)\"$"
  ARGS apply ${_calib} ${MPCAL_TEST_DATA}/loggers/phone_export_en.csv -o - --out-units g)
