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
    python3 '${_bags}/make_ros2_db3.py' --csv s.csv --out session --in-order
    \"$0\" calibrate s.csv -o csv.json >/dev/null
    \"$0\" calibrate session -o bag.json >/dev/null
    python3 '${CMAKE_CURRENT_SOURCE_DIR}/same_numbers.py' csv.json bag.json \
      provenance.input input.columns input.time_unit"
    $<TARGET_FILE:mpcal_cli>
  WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
set_tests_properties(cli.calibrate_bag_equals_csv PROPERTIES LABELS cli)

mpcal_cli_test(bag_stamps_out_of_order EXIT 1
  MATCH "^mpcal: error: .*imu_ros2:102: time goes back: 5 s after 5\\.05 s on message 101"
  ARGS detect ${_bags}/imu_ros2)
mpcal_cli_test(bag_topic_of_another_type EXIT 1
  MATCH "^mpcal: error: .*imu_lz4\\.bag: topic '/chatter' is of type std_msgs/String"
  ARGS detect ${_bags}/imu_lz4.bag --topic /chatter)
mpcal_cli_test(bag_with_text_log_units EXIT 1
  MATCH "^mpcal: error: .*imu_cdr_zstd\\.mcap: a recording's sensor_msgs/Imu has its own units"
  ARGS detect ${_bags}/imu_cdr_zstd.mcap --units g)
