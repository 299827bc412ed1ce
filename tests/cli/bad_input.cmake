# Input that cannot hurt: every subcommand that reads files, fed what users
# feed it by mistake. Each case: exit 1 (2 for a bad flag), exactly one line
# `mpcal: error: ...` (expect.sh checks it), a message that names the
# problem, and no output file left behind. The malformed files are in
# tests/data/bad/ (README there); a few cases are regression tests of fixes.
set(BAD ${MPCAL_TEST_DATA}/bad)
set(GOOD_CALIB ${BAD}/valid_calib.json)
set(GOOD_LOG ${BAD}/too_few_positions.csv)  # reads fine, too few positions
set(GOOD_GNSS ${MPCAL_TEST_DATA}/gnss_rtklib_walk_excerpt.pos)

# Logs: (case name, path, message). The same files go to every reader.
set(bad_logs
  missing      no/such/log.csv             "cannot read log 'no/such/log.csv': No such file"
  directory    ${BAD}                      "is a directory. give the path of a log file"
  empty        ${BAD}/empty.csv            "is empty"
  header_only  ${BAD}/header_only.csv      "header .*no data rows"
  prose        ${BAD}/prose.txt            "prose.txt:[0-9]+: .*not a number"
  binary       ${BAD}/binary.bin           "is not a text log \\(binary data at byte 8\\)"
  binary_text  ${BAD}/binary_no_nul.bin    "is not a text log \\(control characters"
  few_columns  ${BAD}/too_few_columns.csv  "no column for az in the header"
  three_columns ${BAD}/three_columns_no_header.csv "found 3, expected at least 4"
  nan          ${BAD}/nan.csv              "nan.csv:3: non-finite value 'nan' in column 'ax'"
  infinity     ${BAD}/infinity.csv         "infinity.csv:3: non-finite value 'inf' in column 'az'")

# Calibration files: (case name, path, message).
set(bad_calibs
  missing      no/such/calib.json          "cannot read calibration file 'no/such/calib.json'"
  directory    ${BAD}                      "is a directory. give the JSON file"
  empty        ${BAD}/empty.csv            "the file is empty. expected JSON written by 'mpcal calibrate'"
  prose        ${BAD}/prose.txt            "not valid JSON: parse error at line 1, column 1"
  binary       ${BAD}/binary.bin           "is not a text file \\(binary data at byte 8\\)"
  malformed    ${BAD}/malformed.json       "not valid JSON: parse error at line 3"
  not_object   ${BAD}/not_an_object.json   "expected a JSON object .* found an array"
  version2     ${BAD}/version2.json        "format 'mpcal.accelerometer/2' is version 2 .* this mpcal reads version 1"
  overflow     ${BAD}/nonfinite.json       "number overflow parsing '1e999'"
  null_value   ${BAD}/null_value.json      "field 'bias_mps2\\[1\\]' is null")
# repeat tells calibration files from logs by their .json name: the others
# are logs to it (and covered above).
set(bad_calib_json ${bad_calibs})
list(REMOVE_AT bad_calib_json 3 4 5 6 7 8 9 10 11 12 13 14)

# Runs the cases of `list` (triplets) as NAME_PREFIX_<case>, with @IN@ in the
# arguments replaced by the case's path.
function(bad_input_cases prefix list absent)
  set(args ${ARGN})
  list(LENGTH list n)
  math(EXPR last "${n} - 1")
  foreach(i RANGE 0 ${last} 3)
    math(EXPR j "${i} + 1")
    math(EXPR k "${i} + 2")
    list(GET list ${i} name)
    list(GET list ${j} path)
    list(GET list ${k} match)
    list(TRANSFORM args REPLACE "^@IN@$" "${path}" OUTPUT_VARIABLE case_args)
    mpcal_cli_test(${prefix}_${name} EXIT 1 MATCH "${match}" ABSENT ${absent}
      ARGS ${case_args})
  endforeach()
endfunction()

bad_input_cases(bad_calibrate "${bad_logs}" out.json calibrate @IN@ -o out.json)
bad_input_cases(bad_detect "${bad_logs}" out.json detect @IN@ --json out.json)
bad_input_cases(bad_apply_log "${bad_logs}" out.csv apply ${GOOD_CALIB} @IN@ -o out.csv)
bad_input_cases(bad_repeat_log "${bad_logs}" out.json repeat ${GOOD_CALIB} @IN@ --json out.json)
bad_input_cases(bad_verify_imu "${bad_logs}" out.json
  verify --imu @IN@ --gnss ${GOOD_GNSS} -o out.json)
bad_input_cases(bad_apply_calib "${bad_calibs}" out.csv apply @IN@ ${GOOD_LOG} -o out.csv)
bad_input_cases(bad_repeat_calib "${bad_calib_json}" out.json repeat ${GOOD_CALIB} @IN@ --json out.json)
bad_input_cases(bad_verify_calib "${bad_calibs}" out.json
  verify --imu ${GOOD_LOG} --gnss ${GOOD_GNSS} --calib @IN@ -o out.json)

# Sessions that read but cannot be calibrated.
mpcal_cli_test(bad_calibrate_never_still EXIT 1 MATCH "no static position found .* never stops moving"
  ABSENT out.json ARGS calibrate ${BAD}/never_still.csv -o out.json)
mpcal_cli_test(bad_detect_never_still EXIT 1 MATCH "no static position found .* never stops moving"
  ARGS detect ${BAD}/never_still.csv)
mpcal_cli_test(bad_calibrate_too_few_positions EXIT 1
  MATCH "5 static positions.* needs at least 10"
  ABSENT out.json ARGS calibrate ${BAD}/too_few_positions.csv -o out.json)
mpcal_cli_test(bad_detect_too_few_positions EXIT 1 MATCH "record 5 more positions"
  ARGS detect ${BAD}/too_few_positions.csv)
# Turned only about x: x never sees gravity, its bias and scale are free.
mpcal_cli_test(bad_calibrate_one_axis EXIT 1
  MATCH "do not determine .*bias_x_mps2.*scale_factor_error_x|do not determine all 9 parameters"
  ABSENT out.json ARGS calibrate ${BAD}/one_axis_rotation.csv -o out.json)
mpcal_cli_test(bad_detect_one_axis EXIT 1 MATCH "do not determine all 9 parameters"
  ARGS detect ${BAD}/one_axis_rotation.csv)
mpcal_cli_test(bad_repeat_one_axis EXIT 1 MATCH "one_axis_rotation.csv: .*do not determine"
  ABSENT out.json ARGS repeat ${GOOD_CALIB} ${BAD}/one_axis_rotation.csv --json out.json)
mpcal_cli_test(bad_repeat_single_session EXIT 1 MATCH "at least 2 sessions"
  ABSENT out.json ARGS repeat ${GOOD_CALIB} --json out.json)

# The GNSS reference of verify. A missing one is input (exit 1), not usage
# (regression: it was a CLI11 file check, exit 2).
set(bad_gnss
  missing      no/such/ref.pos             "no/such/ref.pos: cannot open the GNSS reference file"
  directory    ${BAD}                      "is a directory, not a GNSS reference file"
  empty        ${BAD}/empty.csv            "the reference file is empty"
  prose        ${BAD}/prose.txt            "first line must be a header"
  binary       ${BAD}/binary.bin           "is not a text file \\(binary data at byte 8\\)")
bad_input_cases(bad_verify_gnss "${bad_gnss}" out.json
  verify --imu ${GOOD_LOG} --gnss @IN@ -o out.json)

# Outputs: never over an input (same path, another spelling, a link), never
# half-written. Each runs on a copy in its own directory, so that a
# regression cannot damage the checked-in files.
function(bad_output_case name match script)
  add_test(NAME cli.${name}
    COMMAND ${MPCAL_CLI_EXPECT} 1 ${match} --workdir ${CMAKE_CURRENT_BINARY_DIR}/${name}
            -- sh -c "cp '${GOOD_LOG}' log.csv && cp '${GOOD_CALIB}' calib.json && ${script}"
            $<TARGET_FILE:mpcal_cli>)
  set_tests_properties(cli.${name} PROPERTIES LABELS cli)
endfunction()
set(same "is the input file")
bad_output_case(bad_output_calibrate_same ${same} "exec \"$0\" calibrate log.csv -o log.csv")
bad_output_case(bad_output_detect_same ${same} "exec \"$0\" detect log.csv --json ./log.csv")
bad_output_case(bad_output_apply_same_log ${same} "exec \"$0\" apply calib.json log.csv -o log.csv")
# Regression: apply wrote its output over the calibration file it read.
bad_output_case(bad_output_apply_same_calib ${same}
  "\"$0\" apply calib.json log.csv -o calib.json; s=$?; cmp -s calib.json '${GOOD_CALIB}' || s=9; exit $s")
bad_output_case(bad_output_apply_link ${same}
  "ln -sf log.csv link.csv && exec \"$0\" apply calib.json log.csv -o link.csv")
bad_output_case(bad_output_repeat_same ${same}
  "cp calib.json c2.json && exec \"$0\" repeat calib.json c2.json --json c2.json")
bad_output_case(bad_output_verify_same ${same}
  "exec \"$0\" verify --imu log.csv --gnss '${GOOD_GNSS}' -o log.csv")
mpcal_cli_test(bad_output_missing_directory EXIT 1 MATCH "no/such/dir"
  ARGS apply ${GOOD_CALIB} ${GOOD_LOG} -o no/such/dir/out.csv)
mpcal_cli_test(bad_output_is_directory EXIT 1 MATCH "is a directory"
  ARGS simulate static --positions 2 --dwell 1 -o .)
# Regression: a --truth that cannot be written left the log behind.
mpcal_cli_test(bad_output_simulate_truth_unwritable EXIT 1 MATCH "is a directory"
  ABSENT s.csv ARGS simulate static --positions 2 --dwell 1 -o s.csv --truth .)

# simulate's option errors: bad numbers are usage (exit 2) with a message
# that says what is wrong (regression: CLI11 spelled out DBL_MAX digit by
# digit), or invalid combinations (exit 1).
mpcal_cli_test(bad_simulate_negative_rate EXIT 2 MATCH "--rate: must be a positive number, got '-1'"
  ABSENT s.csv ARGS simulate static --rate -1 -o s.csv)
mpcal_cli_test(bad_simulate_infinite_rate EXIT 2 MATCH "--rate: must be a positive number, got 'inf'"
  ABSENT s.csv ARGS simulate static --rate inf -o s.csv)
mpcal_cli_test(bad_simulate_nan_rate EXIT 2 MATCH "--rate: must be a positive number, got 'nan'"
  ABSENT s.csv ARGS simulate static --rate nan -o s.csv)
mpcal_cli_test(bad_simulate_not_a_number EXIT 2 MATCH "--dwell"
  ABSENT s.csv ARGS simulate static --dwell ten -o s.csv)
mpcal_cli_test(bad_simulate_too_long EXIT 1 MATCH "the limit is"
  ABSENT s.csv ARGS simulate static --positions 100000 --dwell 1000 -o s.csv)
mpcal_cli_test(bad_calibrate_zero_range EXIT 2 MATCH "--range: must be a positive number"
  ABSENT out.json ARGS calibrate ${GOOD_LOG} --range 0 -o out.json)

# Clipped readings: --range below 1 g puts every position of this session at
# the limit; they are all dropped and the error says why.
mpcal_cli_test(bad_calibrate_all_clipped EXIT 1
  MATCH "5 dropped because they contain readings at the sensor's range limit \\(\\|x\\| >= 8\\.73773"
  ABSENT out.json ARGS calibrate ${GOOD_LOG} --range 0.9 -o out.json)
mpcal_cli_test(bad_detect_all_clipped EXIT 1
  MATCH "note: position 0\\.8-3\\.4 s dropped: [0-9]+ of its samples are at the sensor's range limit"
  ARGS detect ${GOOD_LOG} --range 0.9)
# Regression: simulate walk left the files written before the one that failed.
mpcal_cli_test(bad_output_walk_truth_unwritable EXIT 1 MATCH "is a directory"
  ABSENT w.csv g.pos ARGS simulate walk -o w.csv --gnss g.pos --truth .)

# Outputs that are not regular files: a device node, a FIFO or a
# link is never replaced by a regular file; /dev/full and a closed or full
# standard output are errors; an empty name is a usage error. Every command
# that writes, each way (tests/cli/output_case.sh makes the node or link).
set(MPCAL_OUTPUT_CASE ${CMAKE_CURRENT_SOURCE_DIR}/output_case.sh)
set(_session ${MPCAL_TEST_DATA}/report/session.csv)
set(_walk_dir ${CMAKE_CURRENT_BINARY_DIR}/simulate_walk_turn)
set(output_cases
  null          0 "exit 0"
  full          1 "No space left on device"
  fifo          0 "exit 0"
  symlink       0 "exit 0"
  fd_link       0 "exit 0"
  stdout        0 "exit 0"
  empty         2 "the file name is empty"
  stdout_full   1 "error writing to standard output"
  stdout_closed 1 "standard output is closed")
function(output_cases command)
  list(LENGTH output_cases n)
  math(EXPR last "${n} - 1")
  foreach(i RANGE 0 ${last} 3)
    math(EXPR j "${i} + 1")
    math(EXPR k "${i} + 2")
    list(GET output_cases ${i} case)
    list(GET output_cases ${j} code)
    list(GET output_cases ${k} match)
    set(name bad_output_${command}_${case})
    add_test(NAME cli.${name}
      COMMAND ${MPCAL_CLI_EXPECT} ${code} ${match} --workdir ${CMAKE_CURRENT_BINARY_DIR}/${name}
              -- ${MPCAL_OUTPUT_CASE} ${case} $<TARGET_FILE:mpcal_cli> ${ARGN})
    set_tests_properties(cli.${name} PROPERTIES LABELS cli TIMEOUT 120)
    if(command STREQUAL "verify")
      set_tests_properties(cli.${name} PROPERTIES FIXTURES_REQUIRED simulated_walk)
    endif()
  endforeach()
endfunction()
output_cases(calibrate calibrate ${_session} -o @OUT@)
output_cases(detect detect ${_session} --json @OUT@)
output_cases(apply apply ${GOOD_CALIB} ${GOOD_LOG} -o @OUT@)
output_cases(repeat repeat ${MPCAL_TEST_DATA}/paper/colibri_trial1.json
  ${MPCAL_TEST_DATA}/paper/colibri_trial2.json --json @OUT@)
output_cases(verify verify --imu ${_walk_dir}/walk.csv --gnss ${_walk_dir}/ref.pos -o @OUT@)
output_cases(report report --calib ${MPCAL_TEST_DATA}/report/calib.json -o @OUT@)
output_cases(simulate simulate static --positions 2 --dwell 1 -o @OUT@)

# Readers given a device: refused at once, not read to the end.
# `timeout` makes a hang fail fast (exit 124, not 1).
function(device_input_case name match)
  add_test(NAME cli.${name}
    COMMAND ${MPCAL_CLI_EXPECT} 1 ${match} --workdir ${CMAKE_CURRENT_BINARY_DIR}/${name}
            -- timeout 20 $<TARGET_FILE:mpcal_cli> ${ARGN})
  set_tests_properties(cli.${name} PROPERTIES LABELS cli)
endfunction()
foreach(dev zero urandom)
  set(calib_dev "'/dev/${dev}' is a character device, not a calibration file")
  device_input_case(bad_device_apply_calib_${dev} ${calib_dev}
    apply /dev/${dev} ${GOOD_LOG} -o out.csv)
  device_input_case(bad_device_report_calib_${dev} ${calib_dev}
    report --calib /dev/${dev} -o out.html)
  device_input_case(bad_device_verify_calib_${dev} ${calib_dev}
    verify --imu ${GOOD_LOG} --gnss ${GOOD_GNSS} --calib /dev/${dev} -o out.json)
  device_input_case(bad_device_verify_gnss_${dev}
    "'/dev/${dev}' is a character device, not a GNSS reference file"
    verify --imu ${GOOD_LOG} --gnss /dev/${dev} -o out.json)
  device_input_case(bad_device_repeat_${dev} "not a text log"
    repeat ${GOOD_CALIB} /dev/${dev} --json out.json)
  device_input_case(bad_device_calibrate_${dev} "not a text log" calibrate /dev/${dev})
  device_input_case(bad_device_detect_${dev} "not a text log" detect /dev/${dev})
  device_input_case(bad_device_apply_log_${dev} "not a text log"
    apply ${GOOD_CALIB} /dev/${dev} -o out.csv)
  device_input_case(bad_device_verify_imu_${dev} "not a text log"
    verify --imu /dev/${dev} --gnss ${GOOD_GNSS} -o out.json)
  device_input_case(bad_device_report_session_${dev} "not a text log"
    report --session /dev/${dev} -o out.html)
endforeach()
# The same through a pipe: the first bytes are checked before the rest.
function(shell_case name code match script)
  add_test(NAME cli.${name}
    COMMAND ${MPCAL_CLI_EXPECT} ${code} ${match} --workdir ${CMAKE_CURRENT_BINARY_DIR}/${name}
            -- bash -c "${script}" $<TARGET_FILE:mpcal_cli>)
  set_tests_properties(cli.${name} PROPERTIES LABELS cli)
endfunction()
shell_case(bad_pipe_apply_calib_urandom 1 "not a text file \\(binary data at byte"
  "timeout 20 \"$0\" apply <(cat /dev/urandom) '${GOOD_LOG}' -o out.csv")
shell_case(bad_pipe_verify_gnss_zero 1 "not a text file \\(binary data at byte 0"
  "timeout 20 \"$0\" verify --imu '${GOOD_LOG}' --gnss <(cat /dev/zero) -o out.json")
shell_case(bad_pipe_repeat_urandom 1 "not a text log"
  "timeout 20 \"$0\" repeat '${GOOD_CALIB}' <(cat /dev/urandom) --json out.json")

# repeat reads each input once: pipes and process substitutions work, for
# calibration files and logs alike ("too few columns").
shell_case(repeat_process_substitution_json 0 "/dev/fd/[0-9]+: calibration file"
  "\"$0\" repeat -v <(cat '${MPCAL_TEST_DATA}/paper/colibri_trial1.json') <(cat '${MPCAL_TEST_DATA}/paper/colibri_trial2.json')")
shell_case(repeat_process_substitution_log 0 "/dev/fd/[0-9]+: calibrated, [0-9]+ positions"
  "\"$0\" repeat -v <(cat '${_session}') '${GOOD_CALIB}'")

# Warnings are held back when the command fails: one line (all
# timestamps zero printed two or three warnings before the error).
shell_case(bad_calibrate_duplicates_one_line 1 "5 static positions.*\\(after a warning: .*duplicated timestamp"
  "awk 'NR==1{print;next}{print;print}' '${GOOD_LOG}' > dup.csv && exec \"$0\" calibrate dup.csv -o out.json")

# Physically impossible readings: an error naming the line (one
# row of 1e308 gave 'threshold -nan', one of 1e20 dropped positions).
shell_case(bad_calibrate_huge_row_1e308 1
  "huge.csv:100: reading '1e308' in column 'ax' \\(index 1\\) is beyond any accelerometer's range"
  "sed '100s/^\\([^,]*\\),[^,]*,/\\1,1e308,/' '${_session}' > huge.csv && exec \"$0\" calibrate huge.csv -o out.json")
shell_case(bad_detect_huge_row_1e20 1
  "huge.csv:200: reading '1e20' in column 'az' \\(index 3\\) is beyond any accelerometer's range"
  "sed '200s/,[^,]*$/,1e20/' '${_session}' > huge.csv && exec \"$0\" detect huge.csv")
shell_case(bad_calibrate_huge_times 1 "a time of [0-9.]+e\\+30[0-9] s is beyond any logger's clock"
  "awk -F, 'NR==1{print;next}{$1=$1*1e300; print}' OFS=, '${_session}' > t.csv && exec \"$0\" calibrate t.csv")
# Times that do not advance, or by less than any sensor samples (regression:
# steps of 1e-300 s gave 'threshold -nan ... never stops moving').
shell_case(bad_calibrate_zero_times 1
  "zero.csv: all 700 rows have the same time, 0 s: the time column does not advance. give --time-unit UNIT or --rate HZ"
  "awk -F, 'NR==1{print;next}{$1=0; print}' OFS=, '${GOOD_LOG}' > zero.csv && exec \"$0\" calibrate zero.csv -o out.json")
shell_case(bad_detect_tiny_steps 1
  "tiny.csv: the time steps are 4e-302 s, shorter than any sensor samples \\(at most 1e\\+06 Hz"
  "awk -F, 'NR==1{print;next}{$1=$1*1e-300; print}' OFS=, '${GOOD_LOG}' > tiny.csv && exec \"$0\" detect tiny.csv")
mpcal_cli_test(bad_calibrate_seconds_read_as_ns EXIT 1
  MATCH "the time steps are 4e-11 s, shorter than any sensor samples"
  ABSENT out.json ARGS calibrate ${GOOD_LOG} --time-unit ns -o out.json)
mpcal_cli_test(bad_calibrate_index_at_absurd_rate EXIT 1
  MATCH "the time steps are 4e-302 s, shorter than any sensor samples"
  ABSENT out.json ARGS calibrate ${GOOD_LOG} --time-unit index --rate 1e300 -o out.json)
mpcal_cli_test(bad_verify_tiny_steps EXIT 1
  MATCH "the time steps are 4e-11 s, shorter than any sensor samples"
  ABSENT out.json ARGS verify --imu ${GOOD_LOG} --time-unit ns --gnss ${GOOD_GNSS} -o out.json)

# Absurd but finite values in a calibration file (a bias of
# 1e308 was applied), in ranges stated once (include/mpcal/plausible.h).
shell_case(bad_apply_huge_bias 1 "'bias_mps2\\[0\\]' = 1e\\+308 is beyond any accelerometer's bias"
  "sed '0,/-0.6860732339999999/s//1e308/' '${GOOD_CALIB}' > c.json && exec \"$0\" apply c.json '${GOOD_LOG}' -o out.csv")
# The repeatability file is read the same way (regression: a bias of 1e308
# printed inf cells in the report).
shell_case(bad_report_repeat_huge_bias 1
  "r.json: 'parameters.bias_mps2.values\\[0\\]\\[0\\]' = 1e\\+308 is beyond any accelerometer's bias"
  "sed '0,/-0.7461164775971995/s//1e308/' '${MPCAL_TEST_DATA}/report/repeat.json' > r.json && \"$0\" report --repeat r.json -o out.html; s=$?; [ -e out.html ] && s=9; exit $s")
shell_case(bad_apply_gravity_out_of_range 1 "'gravity_mps2' = 10.4 is not a magnitude of gravity"
  "sed 's/\"gravity_mps2\": [0-9.]*/\"gravity_mps2\": 10.4/' '${GOOD_CALIB}' > c.json && exec \"$0\" apply c.json '${GOOD_LOG}' -o out.csv")
# verify and report --session run calibrate's units check.
mpcal_cli_test(bad_verify_g_read_as_mps2 EXIT 1 MATCH "look like g: add --units g" ABSENT out.json
  ARGS verify --imu ${MPCAL_REAL_DATA}/rtklib-walk/imu_1730_sf.csv
       --columns t=0,ax=1,ay=2,az=3,gx=4,gy=5,gz=6
       --gnss ${MPCAL_REAL_DATA}/rtklib-walk/gnss_1730_sf.pos -o out.json)
mpcal_cli_test(bad_report_session_counts_as_mps2 EXIT 1 MATCH "look like raw ADC counts"
  ABSENT out.html
  ARGS report --session ${MPCAL_REAL_DATA}/xsens-multiposition/xsens_acc.mat -o out.html)

# An empty path is a usage error (exit 2) for every input and output of every
# command: a shell variable that was never set, not a request for a default.
set(_rd ${MPCAL_TEST_DATA}/report)
set(empty_path_cases
  calibrate_input       "calibrate ''"
  detect_input          "detect ''"
  apply_calibration     "apply '' '${GOOD_LOG}' -o out.csv"
  apply_input           "apply '${GOOD_CALIB}' '' -o out.csv"
  repeat_first          "repeat '' '${GOOD_CALIB}'"
  repeat_second         "repeat '${GOOD_CALIB}' ''"
  verify_imu            "verify --imu '' --gnss '${GOOD_GNSS}' -o out.json"
  verify_gnss           "verify --imu '${GOOD_LOG}' --gnss '' -o out.json"
  verify_calibration    "verify --imu '${GOOD_LOG}' --gnss '${GOOD_GNSS}' --calib '' -o out.json"
  verify_trajectories   "verify --imu '${GOOD_LOG}' --gnss '${GOOD_GNSS}' -o out.json --trajectory-csv ''"
  report_calibration    "report --calib '' -o out.html"
  report_session        "report --session '' -o out.html"
  report_repeat         "report --repeat '' -o out.html"
  report_verify         "report --verify '' -o out.html"
  report_trajectories   "report --verify '${_rd}/result.json' --verify-trajectories '' -o out.html"
  report_noise          "report --noise '' -o out.html"
  simulate_truth        "simulate static --positions 2 --dwell 1 -o out.csv --truth ''"
  simulate_walk_gnss    "simulate walk -o out.csv --gnss ''"
  simulate_walk_path    "simulate walk -o out.csv --gnss out.pos --path ''"
  simulate_noise_output "simulate noise --hours 0.01 -o '' --truth out.json"
  simulate_noise_truth  "simulate noise --hours 0.01 -o out.csv --truth ''"
  demo_output_dir       "demo --output-dir ''")
list(LENGTH empty_path_cases n)
math(EXPR last "${n} - 1")
foreach(i RANGE 0 ${last} 2)
  math(EXPR j "${i} + 1")
  list(GET empty_path_cases ${i} case)
  list(GET empty_path_cases ${j} args)
  shell_case(bad_empty_path_${case} 2 "the (file|directory) name is empty"
    "\"$0\" ${args}; s=$?; for f in out.csv out.json out.html out.pos; do [ -e $f ] && s=9; done; exit $s")
endforeach()

# A walk that never moves verifies nothing (regression: an IMU at rest
# throughout gave a raw start-to-end of 0.00 m and exit 0).
shell_case(bad_verify_imu_never_moves 1
  "still\\.csv: the IMU never moves: the still test finds it at rest over all [0-9.]+ s of the log"
  "awk -F, 'NR==1{print \"t,ax,ay,az\";next}{print $1\",0.001,-0.002,9.80665\"}' '${_walk_dir}/walk.csv' > still.csv && \"$0\" verify --imu still.csv --gnss '${_walk_dir}/ref.pos' -o out.json; s=$?; [ -e out.json ] && s=9; exit $s")
set_tests_properties(cli.bad_verify_imu_never_moves PROPERTIES FIXTURES_REQUIRED simulated_walk)
