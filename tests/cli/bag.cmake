# Robotics recordings read wherever a log is read.
set(_bags ${MPCAL_TEST_DATA}/bags)

# One session calibrated from its CSV and from a ROS 2 bag of the same rows
# (tests/data/bags/make_ros2_db3.py, stamps in order; 128 Hz so that every
# time is a whole number of ns): the same calibration, every number
# identical. The files differ only in the input's name and in the columns
# recorded for the CSV.
add_test(NAME cli.calibrate_bag_equals_csv
  COMMAND sh -c "set -e; rm -rf bag_equals_csv && mkdir bag_equals_csv && cd bag_equals_csv
    \"$0\" simulate static --preset mti-g --gyro --rate 128 --seed 2 --digits 0 -o s.csv >/dev/null
    ${MPCAL_PYTHON} '${_bags}/make_ros2_db3.py' --csv s.csv --out session --in-order
    \"$0\" calibrate s.csv -o csv.json >/dev/null
    \"$0\" calibrate session -o bag.json >/dev/null
    ${MPCAL_PYTHON} '${CMAKE_CURRENT_SOURCE_DIR}/same_numbers.py' csv.json bag.json \
      provenance.input input.columns input.time_unit"
    $<TARGET_FILE:mpcal_cli>
  WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
set_tests_properties(cli.calibrate_bag_equals_csv PROPERTIES LABELS cli)

add_test(NAME cli.calibrate_sorted_bag_equals_csv
  COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/bag_sorted_equals_csv.sh
    $<TARGET_FILE:mpcal_cli> ${_bags} ${CMAKE_CURRENT_SOURCE_DIR}
    ${CMAKE_CURRENT_BINARY_DIR}/sorted_bag_equals_csv)
set_tests_properties(cli.calibrate_sorted_bag_equals_csv PROPERTIES LABELS cli)

# The test files' swapped stamps (rows 100 and 101) are sorted and said in
# one line (the session's 5 positions are too few: exit 1).
mpcal_cli_test(bag_stamps_out_of_order EXIT 1
  MATCH "note: .*imu_ros2: 1 message out of order \\(the furthest 50 ms back\\) put in time order$"
  ARGS detect ${_bags}/imu_ros2 --min-static 0.7 --settle 0.15)
mpcal_cli_test(inspect_bag EXIT 0
  MATCH "header stamps: 1 message out of order \\(the furthest 50 ms back\\); sorted when read"
  ARGS inspect ${_bags}/imu_lz4.bag)
mpcal_cli_test(inspect_text_log_in_g EXIT 0
  MATCH "mean magnitude 9\\.[0-9]+ g: about 9\\.8: the readings are in m/s[^,]*, not g \\(give --units mps2\\)"
  ARGS inspect ${_bags}/session.csv --units g)
mpcal_cli_test(inspect_receive_time_of_a_text_log EXIT 1
  MATCH "^mpcal: error: .*session\\.csv: a text log has one time, its time column.*--time header"
  ARGS inspect ${_bags}/session.csv --time receive)
mpcal_cli_test(inspect_not_a_time EXIT 2
  MATCH "^mpcal: error: --time: 'sent' is not one of: header, receive"
  ARGS inspect ${_bags}/imu_lz4.bag --time sent)
mpcal_cli_test(bag_topic_of_another_type EXIT 1
  MATCH "^mpcal: error: .*imu_lz4\\.bag: topic '/chatter' is of type std_msgs/String"
  ARGS detect ${_bags}/imu_lz4.bag --topic /chatter)
mpcal_cli_test(bag_with_text_log_units EXIT 1
  MATCH "^mpcal: error: .*imu_cdr_zstd\\.mcap: a recording's sensor_msgs/Imu has its own units"
  ARGS detect ${_bags}/imu_cdr_zstd.mcap --units g)

# apply on a recording writes a recording of its kind, read back by the
# other tool's own reader (tests/cli/apply_bag.sh). @mcap/core's packages are
# in tests/tools (scripts/install-deps.sh installs them) unless told.
set(MPCAL_MCAP_PACKAGES "${PROJECT_SOURCE_DIR}/tests/tools" CACHE PATH
  "A directory whose node_modules holds @mcap/core 2.2.2, @mcap/support 1.1.0, @foxglove/cdr 3.5.0 and lz4js 0.2.0")
foreach(fixture IN ITEMS imu_none.bag imu_bz2.bag imu_lz4.bag imu_cdr_zstd.mcap
                         imu_cdr_be_lz4.mcap imu_ros1.mcap imu_cdr_plain.mcap)
  string(REPLACE "." "_" _name ${fixture})
  add_test(NAME cli.apply_bag_${_name}
    COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/apply_bag.sh $<TARGET_FILE:mpcal_cli>
            ${MPCAL_TEST_DATA}/imu_trial_1.json ${_bags} ${fixture} ${MPCAL_MCAP_PACKAGES}
    WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
  set_tests_properties(cli.apply_bag_${_name} PROPERTIES LABELS cli SKIP_RETURN_CODE 77)
endforeach()

mpcal_cli_test(apply_bag_output_of_another_kind EXIT 2
  MATCH "^mpcal: error: --output: '.*imu_lz4\\.bag' is a ROS 1 bag and is corrected into one: name the output '\\*\\.bag'"
  ABSENT out.mcap
  ARGS apply ${MPCAL_TEST_DATA}/imu_trial_1.json ${_bags}/imu_lz4.bag -o out.mcap)
mpcal_cli_test(apply_bag_text_log_flag EXIT 2
  MATCH "^mpcal: error: --out-units: '.*imu_cdr_zstd\\.mcap' is a recording, read and written in m/s² and rad/s"
  ABSENT out.mcap
  ARGS apply ${MPCAL_TEST_DATA}/imu_trial_1.json ${_bags}/imu_cdr_zstd.mcap -o out.mcap --out-units g)
mpcal_cli_test(apply_bag_topic_of_another_type EXIT 1
  MATCH "^mpcal: error: .*imu_none\\.bag: topic '/chatter' is of type std_msgs/String"
  ABSENT out.bag
  ARGS apply ${MPCAL_TEST_DATA}/imu_trial_1.json ${_bags}/imu_none.bag -o out.bag --topic /chatter)
mpcal_cli_test(apply_bag_absent_topic EXIT 1
  MATCH "^mpcal: error: .*imu_ros1\\.mcap: no topic '/imu'; the file holds /chatter \\(std_msgs/String\\), /imu/data \\(sensor_msgs/Imu\\)"
  ABSENT out.mcap
  ARGS apply ${MPCAL_TEST_DATA}/imu_trial_1.json ${_bags}/imu_ros1.mcap -o out.mcap --topic /imu)
mpcal_cli_test(apply_bag_ros2_not_written EXIT 1
  MATCH "^mpcal: error: '.*imu_ros2' is a ROS 2 bag, which is read but not written"
  ARGS apply ${MPCAL_TEST_DATA}/imu_trial_1.json ${_bags}/imu_ros2 -o out.db3)
mpcal_cli_test(apply_bag_onto_itself EXIT 1
  MATCH "^mpcal: error: .*imu_none\\.bag"
  ARGS apply ${MPCAL_TEST_DATA}/imu_trial_1.json ${_bags}/imu_none.bag -o ${_bags}/imu_none.bag)
mpcal_cli_test(apply_noise_with_a_text_log EXIT 2
  MATCH "^mpcal: error: --noise: '.*session\\.csv' is a text log, which has no covariances"
  ABSENT out.csv
  ARGS apply ${MPCAL_TEST_DATA}/imu_trial_1.json ${_bags}/session.csv -o out.csv --noise ${_bags}/session.csv)

# Damaged recordings whose copy would read otherwise than it was written
# (an IMU message before its channel's or connection's record, which the
# copy's summary or index would make readable; a connection given two
# topics): apply refuses them in one line and writes nothing. The MCAP file
# was found by the mcap_bag fuzz target; the bags are make_damaged.py's.
mpcal_cli_test(apply_bag_damaged_channel_after_message EXIT 1
  MATCH "^mpcal: error: .*damaged_reads_back_otherwise\\.mcap: record at byte 251: a message of channel 0 comes before the channel's record \\(topic '/imu/data'\\)"
  ABSENT out.mcap
  ARGS apply ${MPCAL_TEST_DATA}/imu_trial_1.json ${_bags}/damaged_reads_back_otherwise.mcap
       -o out.mcap)
mpcal_cli_test(apply_bag_damaged_connection_after_message EXIT 1
  MATCH "^mpcal: error: .*connection_after_message\\.bag: chunk at byte 4117: a message of connection 0 comes before the connection's record"
  ABSENT out.bag
  ARGS apply ${MPCAL_TEST_DATA}/imu_trial_1.json ${_bags}/connection_after_message.bag
       -o out.bag)
mpcal_cli_test(apply_bag_damaged_connection_given_twice EXIT 1
  MATCH "^mpcal: error: .*connection_given_twice\\.bag: chunk at byte [0-9]+: connection 0 is given twice, as '/chatter' \\(std_msgs/String\\) and as '/imu/data' \\(sensor_msgs/Imu\\)"
  ABSENT out.bag
  ARGS apply ${MPCAL_TEST_DATA}/imu_trial_1.json ${_bags}/connection_given_twice.bag
       -o out.bag)
