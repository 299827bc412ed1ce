#include "mpcal/model.h"

namespace mpcal {

std::string_view ToString(ModelKind kind) {
  switch (kind) {
    case ModelKind::kShinElSheimy9:
      return "shin-el-sheimy-9";
    case ModelKind::kBiasScale6:
      return "bias-scale-6";
  }
  return "unknown";
}

std::optional<ModelKind> ParseModelKind(std::string_view name) {
  for (ModelKind kind : {ModelKind::kShinElSheimy9, ModelKind::kBiasScale6}) {
    if (name == ToString(kind)) return kind;
  }
  return std::nullopt;
}

int ParameterCount(ModelKind kind) { return kind == ModelKind::kShinElSheimy9 ? 9 : 6; }

Eigen::Matrix<double, kNumModelParameters, 1> ToVector(const ErrorModel& m) {
  Eigen::Matrix<double, kNumModelParameters, 1> v;
  m.ToParameters(v.data());
  return v;
}

ErrorModel FromVector(const Eigen::Matrix<double, kNumModelParameters, 1>& v) {
  return ErrorModel::FromParameters(v.data());
}

}  // namespace mpcal
