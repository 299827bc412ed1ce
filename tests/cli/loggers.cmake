# Logs as loggers write them: each calibrates with no hand edit.
# The files and how they were made: tests/data/loggers/README.md.
set(_lg ${MPCAL_TEST_DATA}/loggers)
# Arduino MPU-6050 over serial: noise and boot messages before the header,
# raw counts, `millis` time stamps.
mpcal_cli_test(logger_arduino_serial_boot_text EXIT 0
  MATCH "skipped 4 lines before the header \\(serial boot text or a title\\); the header starts on line 5"
  ARGS calibrate ${_lg}/arduino_mpu6050_serial.txt --units counts -o calib.json)
mpcal_cli_test(logger_arduino_calibrates EXIT 0 MATCH "static positions: 18 used"
  ARGS calibrate -v ${_lg}/arduino_mpu6050_serial.txt --units counts -o calib.json)
# A phone app's export, two locales; `Time (s)` names its unit.
mpcal_cli_test(logger_phone_export_en EXIT 0 MATCH "static positions: 14 used"
  ARGS calibrate -v ${_lg}/phone_export_en.csv -o calib.json)
mpcal_cli_test(logger_phone_export_de EXIT 0 MATCH "static positions: 14 used"
  ARGS calibrate -v ${_lg}/phone_export_de.csv -o calib.json)
# ADXL345 with a sample counter: a clear error without the rate, a
# calibration with it.
mpcal_cli_test(logger_adxl345_index_needs_rate EXIT 1
  MATCH "column 'column 0' steps by exactly 1 on every row: it is a sample index, not a time"
  ABSENT calib.json ARGS calibrate ${_lg}/adxl345_sample_index.txt --units g -o calib.json)
mpcal_cli_test(logger_adxl345_index_with_rate EXIT 0 MATCH "static positions: 18 used"
  ARGS calibrate -v ${_lg}/adxl345_sample_index.txt --units g --rate 100 -o calib.json)
# 12 positions in one hemisphere.
mpcal_cli_test(logger_one_hemisphere EXIT 0 MATCH "static positions: 12 used"
  ARGS calibrate -v ${_lg}/one_hemisphere_12.csv --units g -o calib.json)
# The calibration file records how the log was read: apply reads the same
# logger's logs without the flags repeated (here the rate of the index).
add_test(NAME cli.logger_apply_uses_recorded_layout
  COMMAND ${MPCAL_CLI_EXPECT} 0 "corrected [0-9]+ rows"
          --workdir ${CMAKE_CURRENT_BINARY_DIR}/logger_apply_uses_recorded_layout
          -- sh -c "\"$0\" calibrate '${_lg}/adxl345_sample_index.txt' --units g --rate 100 -o c.json >/dev/null && grep -q '\"columns\": \"t=0,ax=1,ay=2,az=3\"' c.json && exec \"$0\" apply c.json '${_lg}/adxl345_sample_index.txt' -o out.txt"
          $<TARGET_FILE:mpcal_cli>)
set_tests_properties(cli.logger_apply_uses_recorded_layout PROPERTIES LABELS cli)
# The datasheet's sensitivity, recorded as the scale reference.
add_test(NAME cli.logger_counts_per_g_datasheet
  COMMAND ${MPCAL_CLI_EXPECT} 0 "\"scale_reference\": \"datasheet\""
          --workdir ${CMAKE_CURRENT_BINARY_DIR}/logger_counts_per_g_datasheet
          -- sh -c "\"$0\" calibrate '${_lg}/arduino_mpu6050_serial.txt' --units counts --counts-per-g 16384 -o c.json >/dev/null && cat c.json"
          $<TARGET_FILE:mpcal_cli>)
set_tests_properties(cli.logger_counts_per_g_datasheet PROPERTIES LABELS cli)
# And the estimates are the sensor's (make_loggers.py): bias x within the
# noise (1σ about 0.1 mg) of 35.69 mg (0.35 m/s²), -8.16, 29.57 and 12.24 mg.
mpcal_cli_test(logger_arduino_bias EXIT 0 MATCH "^bias x +35\\.[0-9]{3} +0\\.0[0-9]{2} +mg"
  ARGS calibrate ${_lg}/arduino_mpu6050_serial.txt --units counts --counts-per-g 16384)
mpcal_cli_test(logger_phone_de_bias EXIT 0 MATCH "^bias x +-8\\.[0-9]{3} +0\\.[01][0-9]{2} +mg"
  ARGS calibrate ${_lg}/phone_export_de.csv)
mpcal_cli_test(logger_adxl345_bias EXIT 0 MATCH "^bias x +29\\.[0-9]{3} +0\\.0[0-9]{2} +mg"
  ARGS calibrate ${_lg}/adxl345_sample_index.txt --units g --rate 100)
mpcal_cli_test(logger_one_hemisphere_bias EXIT 0 MATCH "^bias x +12\\.[0-9]{3} +0\\.1[0-9]{2} +mg"
  ARGS calibrate ${_lg}/one_hemisphere_12.csv --units g)
# A calibration recorded from one logger (phyphox's named columns), applied to
# a log of another (acc_x...): the recorded columns do not fit (ErrorKind::kColumns),
# so apply reads the log by its own header instead of refusing it.
add_test(NAME cli.logger_apply_falls_back_to_the_header
  COMMAND ${MPCAL_CLI_EXPECT} 0 "corrected 240 rows"
          --workdir ${CMAKE_CURRENT_BINARY_DIR}/logger_apply_falls_back_to_the_header
          -- sh -c "\"$0\" calibrate '${_lg}/phone_export_en.csv' -o c.json >/dev/null && grep -q '\"columns\": \"t=' c.json && exec \"$0\" apply c.json '${MPCAL_TEST_DATA}/apply_log.csv' -o out.csv"
          $<TARGET_FILE:mpcal_cli>)
set_tests_properties(cli.logger_apply_falls_back_to_the_header PROPERTIES LABELS cli)
