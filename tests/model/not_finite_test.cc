// RefuseNotFinite: the first row holding a NaN or an infinity, in views of
// memory that no log reader checked.
#include "mpcal/not_finite.h"

#include <limits>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace mpcal {
namespace {

using ::testing::HasSubstr;

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// `n` rows of the caller's: times 0.01 s apart, readings near gravity.
struct Rows {
  explicit Rows(std::size_t n) : t(n), accel(3 * n, 1.0), gyro(3 * n, 0.01) {
    for (std::size_t i = 0; i < n; ++i) t[i] = 0.01 * static_cast<double>(i);
  }
  RecordingView View(bool with_gyro) const {
    RecordingView v;
    v.time_s = t;
    v.accel = XyzRows(accel.data(), t.size());
    if (with_gyro) v.gyro_radps = XyzRows(gyro.data(), t.size());
    v.source = "<arrays>";
    return v;
  }
  std::vector<double> t, accel, gyro;
};

// The error RefuseNotFinite throws for `rows`, or a failure if none.
NotFiniteError Refusal(const RecordingView& rows, std::size_t begin, std::size_t end) {
  try {
    RefuseNotFinite(rows, begin, end);
  } catch (const NotFiniteError& e) {
    return e;
  }
  ADD_FAILURE() << "no NotFiniteError";
  return NotFiniteError("", RowColumn::kTime, 0, kNan);
}

TEST(RefuseNotFinite, FiniteRowsPass) {
  const Rows rows(10000);
  EXPECT_NO_THROW(RefuseNotFinite(rows.View(true), 0, 10000));
}

TEST(RefuseNotFinite, NamesTheFirstRowAndItsColumnAcrossBlocks) {
  // Rows beyond the first block of 4096 doubles, in the middle of a row.
  Rows rows(10000);
  rows.accel[3 * 6001 + 2] = kInf;
  rows.gyro[3 * 5000 + 1] = kNan;
  rows.t[7000] = kNan;
  const NotFiniteError e = Refusal(rows.View(true), 0, 10000);
  EXPECT_EQ(e.column(), RowColumn::kGyro);
  EXPECT_EQ(e.row(), 5000u);
  EXPECT_EQ(e.kind(), ErrorKind::kInput);
  EXPECT_THAT(e.what(),
              HasSubstr("<arrays>: sample 5000 is not finite: its gyroscope "
                        "reading is nan"));
  // Without a gyroscope the accelerometer's row is the first.
  const NotFiniteError a = Refusal(rows.View(false), 0, 10000);
  EXPECT_EQ(a.column(), RowColumn::kAccel);
  EXPECT_EQ(a.row(), 6001u);
  EXPECT_THAT(a.what(), HasSubstr("its accelerometer reading is inf"));
  // Rows after the bad ones are read alone; before them, nothing is wrong.
  EXPECT_EQ(Refusal(rows.View(false), 6002, 10000).column(), RowColumn::kTime);
  EXPECT_NO_THROW(RefuseNotFinite(rows.View(true), 0, 5000));
}

TEST(RefuseNotFinite, OneColumnAlone) {
  Rows rows(100);
  rows.t[42] = -kInf;
  rows.gyro[3 * 7] = kNan;
  EXPECT_NO_THROW(RefuseNotFinite(rows.View(true), RowColumn::kAccel, 0, 100));
  EXPECT_EQ(Refusal(rows.View(true), 0, 100).row(), 7u);
  try {
    RefuseNotFinite(rows.View(true), RowColumn::kTime, 0, 100);
    FAIL();
  } catch (const NotFiniteError& e) {
    EXPECT_EQ(e.row(), 42u);
    EXPECT_THAT(e.what(), HasSubstr("its time is -inf"));
  }
}

}  // namespace
}  // namespace mpcal
