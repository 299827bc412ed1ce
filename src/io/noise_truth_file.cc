// The truth of a simulated still record (mpcal.noise_truth/1), and the record
// itself as CSV, written row by row.
#include <algorithm>
#include <charconv>
#include <string>

#include <nlohmann/json.hpp>

#include "io/json_text.h"
#include "mpcal/error.h"
#include "mpcal/noise_file.h"

namespace mpcal {
namespace {

using json = nlohmann::ordered_json;

void AppendNumber(std::string& buf, double v, int digits) {
  char tmp[64];
  const auto res =
      digits > 0
          ? std::to_chars(tmp, tmp + sizeof tmp, v, std::chars_format::general, digits)
          : std::to_chars(tmp, tmp + sizeof tmp, v);
  buf.append(tmp, res.ptr);
}

}  // namespace

std::string NoiseTruthJson(const NoiseSimulationOptions& o) {
  json j;
  j["format"] = "mpcal.noise_truth/1";
  j["duration_s"] = o.duration_s;
  j["rate_hz"] = o.rate_hz;
  j["seed"] = o.seed;
  j["bias_instability_model"] =
      "flicker: sum of first-order Gauss-Markov processes, two per decade of correlation "
      "time";
  j["flicker_min_tau_s"] = o.flicker_min_tau_s;
  for (const bool gyro : {false, true}) {
    const auto& axes = gyro ? o.gyro_radps : o.accel_mps2;
    json s;
    const Eigen::Vector3d& mean = gyro ? o.gyro_mean_radps : o.accel_mean_mps2;
    s[gyro ? "mean_radps" : "mean_mps2"] = {mean.x(), mean.y(), mean.z()};
    const NoiseTerm terms[3] = {
        NoiseTerm::kWhiteNoise, NoiseTerm::kBiasInstability, NoiseTerm::kRandomWalk};
    for (const NoiseTerm t : terms) {
      json v = json::array();
      for (const AxisNoiseTruth& a : axes) {
        v.push_back(t == NoiseTerm::kWhiteNoise        ? a.white_noise
                    : t == NoiseTerm::kBiasInstability ? a.bias_instability
                                                       : a.random_walk);
      }
      s[NoiseTermKey(t, gyro)] = v;
    }
    j[gyro ? "gyroscope" : "accelerometer"] = s;
  }
  return FiniteJsonText(j, 1, "the noise truth");
}

void WriteImuCsv(
    std::ostream& out,
    const std::function<bool(double*, Eigen::Vector3d*, Eigen::Vector3d*)>& next,
    int digits,
    std::size_t rows,
    const std::function<void(double)>& progress) {
  out << "t,ax,ay,az,gx,gy,gz\n";
  std::string buf;
  buf.reserve(1 << 20);
  double t = 0.0;
  Eigen::Vector3d a, g;
  std::size_t row = 0;
  const std::size_t report_every = std::max<std::size_t>(rows / 100, 1);
  while (next(&t, &a, &g)) {
    AppendNumber(buf, t, 0);
    for (int i = 0; i < 3; ++i) buf.push_back(','), AppendNumber(buf, a[i], digits);
    for (int i = 0; i < 3; ++i) buf.push_back(','), AppendNumber(buf, g[i], digits);
    buf.push_back('\n');
    if (buf.size() > (1 << 20) - 256) {
      out.write(buf.data(), static_cast<std::streamsize>(buf.size()));
      buf.clear();
    }
    if (progress && ++row % report_every == 0) progress(static_cast<double>(row) / rows);
  }
  out.write(buf.data(), static_cast<std::streamsize>(buf.size()));
  if (!out) throw Error("writing the record failed (disk full?)");
}

}  // namespace mpcal
