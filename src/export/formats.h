// The formats of the registry, one function per consumer's file beside this
// one (kalibr.cc, openvins.cc, imu_tk.cc, ...), each returning its entry.
#pragma once

#include "mpcal/export.h"

namespace mpcal::export_formats {

ExportFormat Kalibr();
ExportFormat KalibrScaleMisalignment();
ExportFormat OpenVins();
ExportFormat ImuTk();
ExportFormat ImuTkAccel();
ExportFormat ImuTkGyro();

}  // namespace mpcal::export_formats
