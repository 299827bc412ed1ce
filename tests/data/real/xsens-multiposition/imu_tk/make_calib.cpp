// Runs imu_tk's own MultiPosCalibration on the Xsens recording with the
// settings of its apps/test_imu_calib.cpp, verbose output off (no plots),
// and saves with CalibratedTriad_::save.
#include <iostream>
#include "imu_tk/io_utils.h"
#include "imu_tk/calibration.h"
#include "imu_tk/visualization.h"
using namespace imu_tk; using namespace Eigen; using namespace std;
// Plot symbols are referenced only under verbose output (off here).
namespace imu_tk { Plot::Plot() {} void waitForKey() {}
template <> void Plot::plotIntervals<double>(const std::vector<TriadData_<double>>&, const std::vector<DataInterval>&, DataInterval) {}
template <> void Plot::plotIntervals<float>(const std::vector<TriadData_<float>>&, const std::vector<DataInterval>&, DataInterval) {} }
int main(int argc, char** argv) {
  vector<TriadData> acc_data, gyro_data;
  importAsciiData(argv[1], acc_data, imu_tk::TIMESTAMP_UNIT_SEC);
  importAsciiData(argv[2], gyro_data, imu_tk::TIMESTAMP_UNIT_SEC);
  CalibratedTriad init_acc_calib, init_gyro_calib;
  init_acc_calib.setBias(Vector3d(32768, 32768, 32768));
  init_gyro_calib.setScale(Vector3d(1.0/6258.0, 1.0/6258.0, 1.0/6258.0));
  MultiPosCalibration mp_calib;
  mp_calib.setInitStaticIntervalDuration(50.0);
  mp_calib.setInitAccCalibration(init_acc_calib);
  mp_calib.setInitGyroCalibration(init_gyro_calib);
  mp_calib.setGravityMagnitude(9.81744);
  mp_calib.enableVerboseOutput(false);
  mp_calib.enableAccUseMeans(false);
  mp_calib.calibrateAccGyro(acc_data, gyro_data);
  mp_calib.getAccCalib().save("xsens_acc.calib");
  mp_calib.getGyroCalib().save("xsens_gyro.calib");
  return 0;
}
