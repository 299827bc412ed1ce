// Readers of GNSS reference tracks on real-format files, good and malformed.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "mpcal/error.h"
#include "mpcal/gnss.h"
#include "test_util.h"

namespace mpcal {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;
using testing::RealDataPath;
using testing::TestDataPath;
using ::testing::ThrowsMessage;

// The excerpt's first epoch, 2025/08/28 17:30:49.749 on its own clock
// (date -u -d '2025-08-28 17:30:49.749' +%s.%N).
constexpr double kExcerptStartS = 1756402249.749;
// Millisecond timestamps stored as doubles near 1.7e9 s.
constexpr double kTimeTolS = 1e-5;
// The test files print positions to 1e-4 m (ECEF), 1e-9 deg, 1e-5 arcsec
// (dms, 0.3 mm) or 1e-5 arcmin (NMEA, 2 cm): tolerances just above each.
constexpr double kEcefTolM = 1e-3;
constexpr double kDmsTolM = 1e-3;
constexpr double kNmeaTolM = 0.02;
// The real excerpt's heights are printed to the millimetre.
constexpr double kMillimetre = 1e-3;

GnssTrack Excerpt() { return ReadGnss(TestDataPath("gnss_rtklib_walk_excerpt.pos")); }

TEST(RtklibPos, ReadsRealWalkExcerptInGpst) {
  const GnssTrack t = Excerpt();
  ASSERT_EQ(t.size(), 40u);
  EXPECT_EQ(t.time_system, TimeSystem::kGpst);
  EXPECT_NEAR(t.time_s.front(), kExcerptStartS, kTimeTolS);
  EXPECT_NEAR(t.time_s[1] - t.time_s[0], 0.25, kTimeTolS);
  ASSERT_TRUE(t.origin.has_value());
  EXPECT_DOUBLE_EQ(t.origin->latitude_deg, 40.0966916);
  EXPECT_DOUBLE_EQ(t.origin->longitude_deg, -105.1471663);
  EXPECT_DOUBLE_EQ(t.origin->height_m, 1601.451);
  EXPECT_TRUE(t.enu_m.front().isZero());
  // RTKLIB writes Q as "1.0000000" here; 36 fixed, 4 float epochs.
  EXPECT_EQ(std::count(t.quality.begin(), t.quality.end(), 1), 36);
  EXPECT_EQ(std::count(t.quality.begin(), t.quality.end(), 2), 4);
  EXPECT_TRUE(t.warnings.empty());
}

TEST(RtklibPos, EnuAgreesWithGeographicLibAtEveryEpoch) {
  // Line 2 of the excerpt holds the origin; line 41 the last epoch.
  const GnssTrack t = Excerpt();
  const Geodetic last{40.0966604, -105.1471499, 1601.736};
  const Eigen::Vector3d expected = GeodeticToEnu(*t.origin, last);
  // The walker went south-east: 3.1e-5 deg south (3.5 m), 1.64e-5 deg east
  // (1.4 m); this checks the sign and order of the axes too.
  EXPECT_NEAR(expected.x(), 1.40, 0.01);
  EXPECT_NEAR(expected.y(), -3.46, 0.01);
  EXPECT_NEAR((t.enu_m.back() - expected).norm(), 0.0, kMillimetre)
      << t.enu_m.back().transpose() << " vs " << expected.transpose();
}

TEST(RtklibPos, ReadsTheWholeRealWalk) {
  const GnssTrack t = ReadGnss(RealDataPath("rtklib-walk/gnss_1730_sf.pos"));
  ASSERT_EQ(t.size(), 536u);
  // The data README: a closed loop, start and end 0.2 m apart.
  const Eigen::Vector3d d = t.enu_m.back() - t.enu_m.front();
  EXPECT_NEAR(std::hypot(d.x(), d.y()), 0.19, 0.02);
  int fixed = 0;
  for (const int q : t.quality) fixed += q == 1 ? 1 : 0;
  EXPECT_EQ(fixed, 349);
}

TEST(RtklibPos, QualityFilterDropsFloatEpochsWithAWarning) {
  GnssReadOptions options;
  options.max_rtklib_quality = 1;
  const GnssTrack t = ReadGnss(RealDataPath("rtklib-walk/gnss_1730_sf.pos"), options);
  EXPECT_EQ(t.size(), 349u);
  ASSERT_EQ(t.warnings.size(), 1u);
  EXPECT_THAT(t.warnings[0], HasSubstr("dropped 187 epochs"));
}

TEST(RtklibPos, EcefColumnsGiveTheSameTrack) {
  const GnssTrack ecef = ReadGnss(TestDataPath("gnss_rtklib_ecef.pos"));
  const GnssTrack llh = Excerpt();
  ASSERT_EQ(ecef.size(), 10u);
  EXPECT_NEAR(ecef.origin->latitude_deg, 40.0966916, 1e-8);
  for (std::size_t i = 0; i < ecef.size(); ++i) {
    EXPECT_NEAR(ecef.time_s[i], llh.time_s[i], kTimeTolS);
    EXPECT_NEAR((ecef.enu_m[i] - llh.enu_m[i]).norm(), 0.0, kEcefTolM) << "epoch " << i;
  }
}

TEST(RtklibPos, GpsWeekAndTimeOfWeekGiveTheCalendarTime) {
  const GnssTrack tow = ReadGnss(TestDataPath("gnss_rtklib_tow.pos"));
  const GnssTrack llh = Excerpt();
  ASSERT_EQ(tow.size(), 10u);
  for (std::size_t i = 0; i < tow.size(); ++i) {
    EXPECT_NEAR(tow.time_s[i], llh.time_s[i], kTimeTolS);
  }
}

TEST(RtklibPos, UtcWithDegreesMinutesSeconds) {
  const GnssTrack dms = ReadGnss(TestDataPath("gnss_rtklib_utc_dms.pos"));
  const GnssTrack llh = Excerpt();
  EXPECT_EQ(dms.time_system, TimeSystem::kUtc);
  ASSERT_EQ(dms.size(), 10u);
  EXPECT_NEAR(dms.origin->longitude_deg, -105.1471663, 1e-8);
  for (std::size_t i = 0; i < dms.size(); ++i) {
    EXPECT_NEAR((dms.enu_m[i] - llh.enu_m[i]).norm(), 0.0, kDmsTolM);
  }
}

TEST(RtklibPos, WrittenFileReadsBack) {
  const Geodetic origin{-25.45, -49.233, 935.0};
  std::vector<PosEpoch> epochs;
  for (int i = 0; i < 20; ++i) {
    PosEpoch e;
    e.time_s = 1715508000.0 + 0.2 * i;
    e.position = EnuToGeodetic(origin, Eigen::Vector3d(1.5 * i, -0.7 * i, 0.01 * i));
    e.quality = i < 10 ? 1 : 2;
    epochs.push_back(e);
  }
  const GnssTrack t = ParseGnss(FormatRtklibPos(epochs), "written.pos");
  ASSERT_EQ(t.size(), 20u);
  EXPECT_EQ(t.time_system, TimeSystem::kGpst);
  for (int i = 0; i < 20; ++i) {
    EXPECT_NEAR(t.time_s[i], epochs[i].time_s, kTimeTolS);
    // 1e-9 deg is 0.1 mm; the height is written to 0.1 mm.
    EXPECT_NEAR(
        (t.enu_m[i] - Eigen::Vector3d(1.5 * i, -0.7 * i, 0.01 * i)).norm(), 0.0, 3e-4);
    EXPECT_EQ(t.quality[i], i < 10 ? 1 : 2);
  }
}

TEST(RtklibPos, TimeJustBelowAMinuteDoesNotPrintSixtySeconds) {
  PosEpoch e;
  e.time_s = 1715508059.9996;  // rounds to the next minute
  const std::string text = FormatRtklibPos({e});
  EXPECT_THAT(text, HasSubstr("2024/05/12 10:01:00.000"));
}

TEST(Geodetic, EnuRoundTrip) {
  const Geodetic origin{40.0966916, -105.1471663, 1601.451};
  const Eigen::Vector3d enu(123.4, -56.7, 8.9);
  const Geodetic g = EnuToGeodetic(origin, enu);
  // GeographicLib's round trip is good to a few nanometres.
  EXPECT_NEAR((GeodeticToEnu(origin, g) - enu).norm(), 0.0, 1e-8);
}

TEST(Nmea, ReadsGgaWithTheDateOfRmcAndSkipsBadSentences) {
  const GnssTrack t = ReadGnss(TestDataPath("gnss_walk.nmea"));
  const GnssTrack llh = Excerpt();
  EXPECT_EQ(t.time_system, TimeSystem::kUtc);
  // 10 GGA: one with a bad checksum, one without a fix.
  ASSERT_EQ(t.size(), 8u);
  EXPECT_NEAR(t.time_s.front(), std::floor(kExcerptStartS * 100.0) / 100.0, kTimeTolS);
  // Ellipsoidal height = altitude + geoid separation, as in the .pos.
  EXPECT_NEAR(t.origin->height_m, 1601.451, kMillimetre);
  EXPECT_EQ(t.quality.front(), 4);
  const std::vector<std::size_t> kept = {0, 1, 2, 4, 6, 7, 8, 9};
  for (std::size_t i = 0; i < kept.size(); ++i) {
    EXPECT_NEAR((t.enu_m[i] - llh.enu_m[kept[i]]).norm(), 0.0, kNmeaTolM)
        << "epoch " << i;
  }
  ASSERT_EQ(t.warnings.size(), 2u);
  // Line 8 holds the 4th GGA, the one with the bad checksum (RMC, then GGA
  // and GSA pairs).
  EXPECT_THAT(t.warnings[0], HasSubstr("bad checksum (first at line 8)"));
  EXPECT_THAT(t.warnings[1], HasSubstr("1 GGA sentences without a fix"));
}

TEST(Nmea, MidnightWithoutADateRollsOver) {
  const GnssTrack t = ReadGnss(TestDataPath("gnss_midnight.nmea"));
  ASSERT_EQ(t.size(), 3u);
  EXPECT_NEAR(t.time_s[0], 86399.8, kTimeTolS);
  EXPECT_NEAR(t.time_s[1], 86400.0, kTimeTolS);
  EXPECT_NEAR(t.time_s[2], 86400.2, kTimeTolS);
  ASSERT_FALSE(t.warnings.empty());
  EXPECT_THAT(t.warnings[0], HasSubstr("no date"));
}

TEST(Csv, GeodeticColumnsWithQuality) {
  const GnssTrack t = ReadGnss(TestDataPath("gnss_llh.csv"));
  const GnssTrack llh = Excerpt();
  ASSERT_EQ(t.size(), 10u);
  EXPECT_EQ(t.time_system, TimeSystem::kUnknown);
  EXPECT_NEAR(t.time_s[0], kExcerptStartS, kTimeTolS);
  for (std::size_t i = 0; i < t.size(); ++i) {
    EXPECT_NEAR((t.enu_m[i] - llh.enu_m[i]).norm(), 0.0, kMillimetre);
    EXPECT_EQ(t.quality[i], 1);
  }
}

TEST(Csv, LocalColumnsAreKeptAsTheyAre) {
  const GnssTrack t = ReadGnss(TestDataPath("gnss_enu.csv"));
  ASSERT_EQ(t.size(), 10u);
  EXPECT_FALSE(t.origin.has_value());
  EXPECT_DOUBLE_EQ(t.time_s[3], 100.6);
  EXPECT_DOUBLE_EQ(t.enu_m[3].x(), 0.72);
  EXPECT_DOUBLE_EQ(t.enu_m[3].y(), 0.3);
  EXPECT_DOUBLE_EQ(t.enu_m[3].z(), 0.01);
}

// Each malformed file names itself, the line and the field.
struct BadFile {
  const char* name;
  std::vector<const char*> message;
};

class MalformedReference : public ::testing::TestWithParam<BadFile> {};

TEST_P(MalformedReference, ThrowsNamingFileLineAndField) {
  const BadFile& bad = GetParam();
  try {
    ReadGnss(TestDataPath(bad.name));
    FAIL() << bad.name << " was accepted";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_THAT(what, HasSubstr(bad.name));
    for (const char* part : bad.message) EXPECT_THAT(what, HasSubstr(part));
  }
}

INSTANTIATE_TEST_SUITE_P(
    Files,
    MalformedReference,
    ::testing::Values(BadFile{"gnss_bad_latitude.pos",
                              {":4:", "latitude is '40.09x6916'"}},
                      BadFile{"gnss_time_back.pos", {":5:", "time goes back by 0.250 s"}},
                      BadFile{"gnss_no_header.pos", {"cannot tell the format"}},
                      BadFile{"gnss_short_line.pos", {":6:", "4 fields"}},
                      BadFile{"gnss_bad_latitude.nmea", {":5:", "latitude '4005.8O1,N'"}},
                      BadFile{"gnss_short_row.csv", {":3:", "3 fields"}},
                      BadFile{"gnss_no_header.csv", {"cannot tell the format"}}));

TEST(ReadGnss, PosWithoutHeaderAsPosSaysWhatIsMissing) {
  GnssReadOptions options;
  options.format = GnssFormat::kRtklibPos;
  EXPECT_THAT([&] { ReadGnss(TestDataPath("gnss_no_header.pos"), options); },
              ThrowsMessage<Error>(
                  AllOf(HasSubstr("gnss_no_header.pos:1"), HasSubstr("column header"))));
}

TEST(ReadGnss, CsvWithoutHeaderAsCsvAsksForOne) {
  GnssReadOptions options;
  options.format = GnssFormat::kCsv;
  EXPECT_THAT([&] { ReadGnss(TestDataPath("gnss_no_header.csv"), options); },
              ThrowsMessage<Error>(HasSubstr("must be a header")));
}

TEST(ReadGnss, MissingEmptyAndDirectoryAreErrors) {
  const testing::ScratchDir dir;
  EXPECT_THAT([&] { ReadGnss(dir.Path("nope.pos")); },
              ThrowsMessage<Error>(HasSubstr("cannot open")));
  EXPECT_THAT([&] { ReadGnss(dir.Write("empty.pos", "")); },
              ThrowsMessage<Error>(HasSubstr("empty")));
  EXPECT_THAT([&] { ReadGnss(dir.path().string()); },
              ThrowsMessage<Error>(HasSubstr("is a directory")));
}

TEST(ReadGnss, HeaderOnlyHasNoEpochs) {
  EXPECT_THAT(
      [] {
        ParseGnss("%  GPST  latitude(deg) longitude(deg) height(m) Q ns\n", "h.pos");
      },
      ThrowsMessage<Error>(HasSubstr("no position epochs")));
  EXPECT_THAT([] { ParseGnss("$GPGSA,A,3,01,,,,,,,,,,,,1.2,0.6,1.0*2A\n", "x.nmea"); },
              ThrowsMessage<Error>(HasSubstr("no GGA")));
}

TEST(ReadGnss, OutOfRangeValuesAreErrors) {
  const std::string header = "%  GPST  latitude(deg) longitude(deg) height(m) Q ns\n";
  EXPECT_THAT(
      [&] { ParseGnss(header + "2025/08/28 17:30:39.749 95.0 10.0 0 1 5\n", "a.pos"); },
      ThrowsMessage<Error>(HasSubstr("a.pos:2: latitude 95")));
  EXPECT_THAT(
      [&] { ParseGnss(header + "2025/02/30 17:30:39.749 45.0 10.0 0 1 5\n", "b.pos"); },
      ThrowsMessage<Error>(HasSubstr("b.pos:2: date 2025/02/30 does not exist")));
  EXPECT_THAT(
      [&] { ParseGnss(header + "2025/02/03 25:30:39.749 45.0 10.0 0 1 5\n", "c.pos"); },
      ThrowsMessage<Error>(HasSubstr("c.pos:2: time")));
  EXPECT_THAT(
      [&] { ParseGnss(header + "2025/02/03 12:30:39.749 45.0 nan 0 1 5\n", "d.pos"); },
      ThrowsMessage<Error>(HasSubstr("d.pos:2: longitude is 'nan'")));
}

TEST(ReadGnss, RepeatedTimeIsDroppedWithAWarning) {
  const std::string text =
      "%  GPST  latitude(deg) longitude(deg) height(m) Q ns\n"
      "2025/08/28 17:30:39.749 45.0 10.0 0 1 5\n"
      "2025/08/28 17:30:39.749 45.0 10.0 0 1 5\n"
      "2025/08/28 17:30:39.999 45.0 10.0 0 1 5\n";
  const GnssTrack t = ParseGnss(text, "dup.pos");
  EXPECT_EQ(t.size(), 2u);
  ASSERT_EQ(t.warnings.size(), 1u);
  EXPECT_THAT(t.warnings[0], HasSubstr("repeated time"));
}

TEST(GnssReadOptions, DefaultsAreValidAndBadQualityIsNamed) {
  EXPECT_EQ(GnssReadOptions{}.Validate(), "");
  GnssReadOptions o;
  o.max_rtklib_quality = 7;
  EXPECT_THAT(o.Validate(), HasSubstr("max_rtklib_quality"));
}

TEST(GnssFormat, NamesRoundTrip) {
  for (const GnssFormat f :
       {GnssFormat::kAuto, GnssFormat::kRtklibPos, GnssFormat::kNmea, GnssFormat::kCsv}) {
    EXPECT_EQ(ParseGnssFormat(ToString(f)), f);
  }
  EXPECT_FALSE(ParseGnssFormat("gpx").has_value());
}

// An unknown format is a fact with its remedy: the Option that names the
// format (the command line spells it as its flag).
TEST(GnssReader, UnknownFormatAdvisesNamingTheFormat) {
  try {
    ParseGnss("12 34 56\n", "ref.txt");
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kFormat);
    EXPECT_THAT(e.what(), HasSubstr("ref.txt: cannot tell the format of the reference"));
    ASSERT_EQ(e.advice().settings.size(), 1u);
    EXPECT_EQ(e.advice().settings[0].option, Option::kGnssFormat);
  }
}

// The writer names the program the caller gives; the reader reads it back.
TEST(GnssReader, RtklibPosNamesTheProgramGiven) {
  PosEpoch e;
  e.time_s = 1.7e9;
  e.position = {45.0, 7.0, 300.0};
  e.quality = 1;
  const std::string text = FormatRtklibPos({e}, TimeSystem::kGpst, "my tool");
  EXPECT_THAT(text, HasSubstr("% program   : my tool\n"));
  EXPECT_EQ(ParseGnss(text, "w.pos").size(), 1u);
}

}  // namespace
}  // namespace mpcal
