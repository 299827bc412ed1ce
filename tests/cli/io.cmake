# Reading logs: every malformed input gets one line `mpcal: error: ...` naming
# the file, the line and what was expected (through `mpcal apply`, which
# reads with the same reader and options as `mpcal calibrate`).
set(_calib ${MPCAL_TEST_DATA}/apply_calib.json)
foreach(_case
    "missing|nope.csv|cannot read log .*nope.csv.*No such file"
    "directory|.|is a directory"
    "empty|log_empty.csv|log_empty.csv' is empty"
    "header_only|log_header_only.csv|has a header .*but no data rows"
    "prose|log_prose.txt|log_prose.txt:2: expected a row of numbers"
    "binary|log_binary.bin|not a text log"
    "too_few_columns|log_too_few_columns.txt|log_too_few_columns.txt:1: too few columns: found 3"
    "nan|log_nan.csv|log_nan.csv:3: non-finite value 'nan' in column 'ay'"
    "malformed|log_malformed.csv|log_malformed.csv:3: expected at least 4 columns")
  string(REPLACE "|" ";" _parts "${_case}")
  list(GET _parts 0 _name)
  list(GET _parts 1 _file)
  list(GET _parts 2 _regex)
  if(_file STREQUAL "nope.csv" OR _file STREQUAL ".")
    set(_path ${_file})
  else()
    set(_path ${MPCAL_TEST_DATA}/${_file})
  endif()
  mpcal_cli_test(io_${_name} EXIT 1 MATCH "${_regex}" ABSENT out.csv
    ARGS apply ${_calib} ${_path} -o out.csv)
endforeach()
mpcal_cli_test(io_truncated_last_line EXIT 0 MATCH "mpcal: warning: .*log_truncated.csv:7: last line is incomplete"
  ARGS apply ${_calib} ${MPCAL_TEST_DATA}/log_truncated.csv -o out.csv)
mpcal_cli_test(io_bad_columns_option EXIT 1 MATCH "columns: unknown key 'temp'"
  ARGS apply ${_calib} ${MPCAL_TEST_DATA}/apply_log.csv -o out.csv --columns temp=1)
mpcal_cli_test(io_unknown_column_name EXIT 1 MATCH "has no column 'acc_north'"
  ARGS apply ${_calib} ${MPCAL_TEST_DATA}/apply_log.csv -o out.csv --columns ax=acc_north)
