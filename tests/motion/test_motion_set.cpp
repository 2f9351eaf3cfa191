// Motion sets (motion_set.hpp), RotD50 / RotD100 (rotd.hpp) and three-component synthesis (synthesis.hpp):
// exact merging, projection, closed forms of RotD, linearity against the single-component spectrum, pyrotd on a
// real pair (computed at test time in .venv-test; skipped without it), and the portable synthetic pair.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <numeric>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/input_errors.hpp"
#include "support/noise_record.hpp"
#include "support/peer_script.hpp"
#include "support/shared_data.hpp"
#include "topple/core/error.hpp"
#include "topple/io/read.hpp"
#include "topple/motion/motion_set.hpp"
#include "topple/motion/rotd.hpp"
#include "topple/motion/spectra.hpp"
#include "topple/motion/synthesis.hpp"
#include "topple/core/units.hpp"

namespace topple {
namespace {

std::vector<double> values(const GroundMotion& m) { return {m.accel_m_s2().begin(), m.accel_m_s2().end()}; }

GroundMotion sampled(double dt, std::size_t n, const auto& f) {
  std::vector<double> a(n);
  for (std::size_t i = 0; i < n; ++i) a[i] = f(static_cast<double>(i) * dt);
  return GroundMotion::uniform(std::move(a), dt);
}

using test::expect_input_error;

// ---- Merging and projection ----

TEST(MotionSet, MergesExactlyAndKeepsAJump) {
  // First: a jump from 1 to 3 at t = 1 (two samples at one instant); second: uniform every 0.5 s.
  const auto h1 = GroundMotion::irregular({0.0, 1.0, 1.0, 2.0}, {0.0, 1.0, 3.0, 0.0});
  const auto h2 = GroundMotion::uniform({0.0, 1.0, 2.0, 1.0, 0.0}, 0.5);
  const MotionSet set = MotionSet::make(h1, &h2, ComponentAzimuths{90.0, 0.0});
  ASSERT_FALSE(set.first().is_uniform());
  EXPECT_EQ(set.first().times_s(), (std::vector<double>{0.0, 0.5, 1.0, 1.0, 1.5, 2.0}));
  // Interpolants at 0.5 and 1.5 are exact in binary (halves of small integers): exact equality.
  EXPECT_EQ(values(set.first()), (std::vector<double>{0.0, 0.5, 1.0, 3.0, 1.5, 0.0}));
  EXPECT_EQ(values(set.second()), (std::vector<double>{0.0, 1.0, 2.0, 2.0, 1.0, 0.0}));
  EXPECT_EQ(set.second().times_s(), set.first().times_s());
}

TEST(MotionSet, SameLatticeDifferentLengthsStaysUniform) {
  // One more sample on the first component, the second ending at 0 (no jump): the union is the first's lattice.
  const auto h1 = GroundMotion::uniform({1.0, 2.0, 3.0, 4.0}, 0.01);
  const auto h2 = GroundMotion::uniform({5.0, 6.0, 0.0}, 0.01);
  const MotionSet set = MotionSet::make(h1, &h2, ComponentAzimuths{0.0, 90.0});
  EXPECT_TRUE(set.first().is_uniform());
  EXPECT_EQ(values(set.second()), (std::vector<double>{5.0, 6.0, 0.0, 0.0}));
}

TEST(MotionSet, ProjectionOnTheComponentsAzimuthsReturnsThem) {
  const auto h1 = GroundMotion::uniform({0.0, 1.0, -2.0, 0.5}, 0.01);
  const auto h2 = GroundMotion::uniform({0.0, 3.0, 1.0, -4.0}, 0.01);
  for (const ComponentAzimuths az : {ComponentAzimuths{90.0, 0.0}, ComponentAzimuths{0.0, 90.0},
                                     ComponentAzimuths{30.0, 300.0}}) {
    const MotionSet set = MotionSet::make(h1, &h2, az);
    // cos of multiples of 90 deg is exact (motion_set.cpp): bit for bit.
    EXPECT_EQ(values(set.projected(az.first_deg)), values(h1));
    EXPECT_EQ(values(set.projected(az.second_deg)), values(h2));
    EXPECT_EQ(values(set.projected(az.first_deg + 180.0)), values(h1.inverted()));
    // 45 deg between them: (a1 + a2) / sqrt 2 to a few ulp.
    const double mid = az.first_deg + 45.0 * az.handedness();
    const auto p = values(set.projected(mid));
    for (std::size_t i = 0; i < p.size(); ++i) {
      EXPECT_NEAR(p[i], (h1.accel_m_s2()[i] + h2.accel_m_s2()[i]) / std::sqrt(2.0), 1e-15 * 8.0);
    }
    const auto [r1, r2] = set.rotated(az.first_deg);
    EXPECT_EQ(values(r1), values(h1));
    // rotated's second is azimuth first + 90 (clockwise): h2 itself when the set is clockwise, else -h2.
    EXPECT_EQ(values(r2), values(az.handedness() > 0 ? h2 : h2.inverted()));
  }
  // On the vertical-free set the 0/90 projections of an east-north pair are its components.
  const MotionSet en = MotionSet::make(h1, &h2, ComponentAzimuths{90.0, 0.0});
  EXPECT_EQ(en.projected(90.0).metadata().azimuth_deg, 90.0);
}

TEST(MotionSet, RefusesWhatIsNotOneRecording) {
  const auto h1 = GroundMotion::uniform(std::vector<double>(1001, 1.0), 0.01);  // 0..10 s
  const auto far = GroundMotion::uniform(std::vector<double>(1001, 1.0), 0.01, 6.0);  // 6..16 s: 4 s in common
  expect_input_error([&] { return MotionSet::make(h1, &far, ComponentAzimuths{90.0, 0.0}); }, "time span",
                     "less than half the longest record");
  const auto long_one = GroundMotion::uniform(std::vector<double>(3001, 1.0), 0.01);  // 0..30 s: 10 s in common
  expect_input_error([&] { return MotionSet::make(h1, &long_one, ComponentAzimuths{90.0, 0.0}); }, "time span",
                     "spans 0 to 30 s");
  // Just over half: accepted, merged exactly (the shorter one is zero after its end).
  const auto longer = GroundMotion::uniform(std::vector<double>(1901, 1.0), 0.01);
  EXPECT_NO_THROW((void)MotionSet::make(h1, &longer, ComponentAzimuths{90.0, 0.0}));
  expect_input_error([&] { return MotionSet::make(h1, &h1, ComponentAzimuths{90.0, 10.0}); }, "azimuths",
                     "must be perpendicular");
  // Unknown azimuths: a set (RotD needs none), but no projection on an azimuth.
  const MotionSet unknown = MotionSet::make(h1, &h1, std::nullopt);
  expect_input_error([&] { return unknown.projected(0.0); }, "azimuth", "azimuths are unknown");
  // A channel the header calls vertical, given as a horizontal one, and the reverse.
  RecordMetadata up;
  up.source_file = "station.UD";
  up.component = "U-D";
  up.vertical = true;
  const auto v = GroundMotion::uniform(std::vector<double>(1001, 1.0), 0.01, 0.0, up);
  expect_input_error([&] { return MotionSet::make(h1, &v, ComponentAzimuths{90.0, 0.0}); }, "component",
                     "vertical channel");
  RecordMetadata ns;
  ns.component = "N-S";
  ns.azimuth_deg = 0.0;
  const auto h = GroundMotion::uniform(std::vector<double>(1001, 1.0), 0.01, 0.0, ns);
  expect_input_error([&] { return MotionSet::make(h1, nullptr, std::nullopt, &h); }, "component",
                     "horizontal channel");
  // One component: only its own direction (or the opposite) can be projected on.
  const MotionSet one = MotionSet::make(h, nullptr, ComponentAzimuths{0.0, 90.0});
  expect_input_error([&] { return one.projected(45.0); }, "azimuth", "only its own direction");
  EXPECT_EQ(values(one.projected(180.0)), values(h.inverted()));
}

TEST(MotionSet, ResolveAzimuthsUserWinsOverHeadersWithAWarning) {
  RecordMetadata m1, m2;
  m1.source_file = "a.EW";
  m1.azimuth_deg = 90.0;
  m2.source_file = "a.NS";
  m2.azimuth_deg = 0.0;
  const auto h1 = GroundMotion::uniform({0.0, 1.0}, 0.01, 0.0, m1);
  const auto h2 = GroundMotion::uniform({0.0, 1.0}, 0.01, 0.0, m2);
  std::vector<std::string> warnings;
  const ComponentAzimuths from_headers = resolve_azimuths(h1, h2, std::nullopt, warnings);
  EXPECT_EQ(from_headers.first_deg, 90.0);
  EXPECT_EQ(from_headers.second_deg, 0.0);
  EXPECT_TRUE(warnings.empty());
  const ComponentAzimuths same = resolve_azimuths(h1, h2, ComponentAzimuths{90.0, 360.0}, warnings);
  EXPECT_EQ(same.second_deg, 360.0);
  EXPECT_TRUE(warnings.empty());  // 360 = 0
  const ComponentAzimuths user = resolve_azimuths(h1, h2, ComponentAzimuths{100.0, 10.0}, warnings);
  EXPECT_EQ(user.first_deg, 100.0);
  ASSERT_EQ(warnings.size(), 2u);
  EXPECT_NE(warnings[0].find("a.EW: the header states azimuth 90 deg, --azimuths uses 100 deg"), std::string::npos)
      << warnings[0];
  const auto plain = GroundMotion::uniform({0.0, 1.0}, 0.01);
  expect_input_error([&] { return resolve_azimuths(h1, plain, std::nullopt, warnings); }, "--azimuths",
                     "does not state the component's azimuth");
}

// ---- Header orientation ----

TEST(RecordOrientation, FromComponentTexts) {
  struct Case {
    const char* text;
    std::optional<double> azimuth;
    bool vertical;
  };
  for (const Case& c : {Case{"N-S", 0.0, false}, Case{"E-W", 90.0, false}, Case{"U-D", std::nullopt, true},
                        Case{"N-S (surface, Dir. 4)", 0.0, false}, Case{"E-W (borehole, Dir. 2)", 90.0, false},
                        Case{"90 DEG", 90.0, false}, Case{"  0 DEG", 0.0, false}, Case{"360 deg", 0.0, false},
                        Case{"UP", std::nullopt, true}, Case{"360", 0.0, false}, Case{"HNE", 90.0, false},
                        Case{"HNN", 0.0, false}, Case{"BNZ", std::nullopt, true}, Case{"HN1", std::nullopt, false},
                        Case{"DOWN", std::nullopt, false}, Case{"FN", std::nullopt, false},
                        Case{"400 DEG", std::nullopt, false}, Case{"", std::nullopt, false},
                        Case{"1: 90 deg", 90.0, false}, Case{"2: Up", std::nullopt, true}}) {
    const io::ComponentOrientation o = io::orientation_from_component(c.text);
    EXPECT_EQ(o.azimuth_deg, c.azimuth) << c.text;
    EXPECT_EQ(o.vertical, c.vertical) << c.text;
  }
}

TEST(RecordOrientation, RealFilesStateTheirChannels) {
  if (!test::have_shared()) GTEST_SKIP() << "../shared is absent";
  struct Case {
    const char* file;
    int channel;
    std::optional<double> azimuth;
    bool vertical;
  };
  // SOURCES.md: CSMIP channels 90 deg, UP, 0 deg; K-NET N-S; KiK-net Dir. 4 (surface N-S); ESM HNE; COSMOS BNZ
  // (vertical); SMC component 360; PEER AT2 states no orientation topple trusts.
  for (const Case& c : {Case{"ce36456p_CE36456.V2", 1, 90.0, false}, Case{"ce36456p_CE36456.V2", 2, std::nullopt, true},
                        Case{"ce36456p_CE36456.V2", 3, 0.0, false}, Case{"AOM0081801241951.NS", 1, 0.0, false},
                        Case{"AICH040010061330.NS2", 1, 0.0, false},
                        Case{"HI.ARS1..HNE.D.20190728.160908.C.ACC.ASC", 1, 90.0, false},
                        Case{"us1000hyfh_akbmrp_AKBMR--n.1000hyfh.BNZ.--.acc.V2c", 1, std::nullopt, true},
                        Case{"0111a.smc", 1, 0.0, false}, Case{"RSN6_IMPVALL.I_I-ELC180.AT2", 1, std::nullopt, false}}) {
    io::ReadOptions r;
    r.channel = c.channel;
    const RecordMetadata m = io::read_motion(test::shared_record(c.file), r).metadata();
    EXPECT_EQ(m.azimuth_deg, c.azimuth) << c.file << " channel " << c.channel;
    EXPECT_EQ(m.vertical, c.vertical) << c.file << " channel " << c.channel;
  }
}

TEST(RecordOrientation, HandWrittenKnetHeaders) {
  // A minimal K-NET file (SOURCES.md layout): 17 header lines, then counts. Dir. E-W and U-D.
  const auto knet = [](const char* dir) {
    return fmt::format("Origin Time       2018/01/24 19:51:00\nLat.              41.0\nLong.             142.0\n"
                       "Depth. (km)       30\nMag.              6.2\nStation Code      AOM008\n"
                       "Station Lat.      40.0\nStation Long.     141.0\nStation Height(m) 10\n"
                       "Record Time       2018/01/24 19:51:10\nSampling Freq(Hz) 100Hz\nDuration Time(s)  0.09\n"
                       "Dir.              {}\nScale Factor      3920(gal)/6182761\nMax. Acc. (gal)   0.001\n"
                       "Last Correction   2018/01/24 19:51:00\nMemo.\n1 2 3 4 5 6 7 8\n1\n", dir);
  };
  const GroundMotion ew = io::parse_motion(knet("E-W"), "hand.EW");
  EXPECT_EQ(ew.metadata().azimuth_deg, 90.0);
  EXPECT_FALSE(ew.metadata().vertical);
  const GroundMotion ud = io::parse_motion(knet("U-D"), "hand.UD");
  EXPECT_FALSE(ud.metadata().azimuth_deg.has_value());
  EXPECT_TRUE(ud.metadata().vertical);
  const GroundMotion odd = io::parse_motion(knet("X"), "hand.X");  // unknown code: nothing guessed
  EXPECT_FALSE(odd.metadata().azimuth_deg.has_value());
  EXPECT_FALSE(odd.metadata().vertical);
}

TEST(RecordOrientation, HandWrittenEsmHeaders) {
  // ESM: the STREAM's SEED code. Z up, N north; HN2 is unoriented (SEED 1/2/3): nothing guessed.
  const auto esm = [](const char* stream) {
    return fmt::format("EVENT_NAME: TEST\nSTATION_CODE: ABC\nSAMPLING_INTERVAL_S: 0.01\nNDATA: 3\nSTREAM: {}\n"
                       "UNITS: cm/s^2\nDATA_TYPE: ACCELERATION\n0.0\n1.0\n0.5\n", stream);
  };
  const GroundMotion z = io::parse_motion(esm("HNZ"), "hand.HNZ.ASC");
  EXPECT_TRUE(z.metadata().vertical);
  EXPECT_FALSE(z.metadata().azimuth_deg.has_value());
  EXPECT_EQ(io::parse_motion(esm("HNN"), "hand.HNN.ASC").metadata().azimuth_deg, 0.0);
  const GroundMotion two = io::parse_motion(esm("HN2"), "hand.HN2.ASC");
  EXPECT_FALSE(two.metadata().azimuth_deg.has_value());
  EXPECT_FALSE(two.metadata().vertical);
}

// ---- RotD: closed forms and linearity ----

TEST(RotD, SecondComponentZeroGivesCos45) {
  // a_2 = 0: Y(theta) = Y_1 |cos theta|; RotD100 = Y_1, RotD50 = Y_1 cos 45 deg (rotd.hpp's derivation).
  const auto h1 = sampled(0.01, 2001, [](double t) { return 3.0 * std::sin(2.0 * kPi * 1.3 * t) * std::exp(-0.2 * t); });
  const auto h2 = GroundMotion::uniform(std::vector<double>(2001, 0.0), 0.01);
  const MotionSet set = MotionSet::make(h1, &h2, ComponentAzimuths{90.0, 0.0});
  const std::vector<double> periods{0.2, 1.0};
  const RotDMeasures r = rotd_measures(set, periods);
  // cos 45 deg: the table's value from the Taylor series agrees with std::cos to an ulp or two: 4e-16 relative.
  const double c45 = std::cos(kPi / 4.0);
  EXPECT_EQ(r.pga_m_s2.rotd100, h1.pga_m_s2());
  EXPECT_EQ(r.pga_m_s2.rotd100_angle_deg, 0.0);
  EXPECT_NEAR(r.pga_m_s2.rotd50, c45 * h1.pga_m_s2(), 4e-16 * h1.pga_m_s2());
  const ResponseSpectrum single = response_spectrum(h1, periods);
  for (std::size_t p = 0; p < periods.size(); ++p) {
    // Same recurrence, same samples: the single-component PSA to round-off (1e-12 relative).
    EXPECT_NEAR(r.psa_m_s2[p].rotd100, single.psa_m_s2[p], 1e-12 * single.psa_m_s2[p]);
    EXPECT_NEAR(r.psa_m_s2[p].rotd50, c45 * single.psa_m_s2[p], 1e-12 * single.psa_m_s2[p]);
  }
}

TEST(RotD, CircularPolarisationIsTheSameAtEveryAngle) {
  // a_1 = A(t) cos wt, a_2 = A(t) sin wt with w dt = 1 deg: a_theta = A(t) cos(wt - theta). The amplitude A(t) rises
  // linearly over the first 10 s to `amp` and stays there to 30 s, so that the oscillators reach their rotating
  // steady state without a start-up transient that would depend on theta.
  const double amp = 2.5;
  const double dt = 0.001;
  const double w = (kPi / 180.0) / dt;
  const auto envelope = [&](double t) { return amp * std::min(1.0, t / 10.0); };
  const auto h1 = sampled(dt, 30001, [&](double t) { return envelope(t) * std::cos(w * t); });
  const auto h2 = sampled(dt, 30001, [&](double t) { return envelope(t) * std::sin(w * t); });
  const MotionSet set = MotionSet::make(h1, &h2, ComponentAzimuths{0.0, 90.0});
  // Periods whose free vibration (excited by the ramp's kinks at 0 and 10 s) has died out by the end: decay
  // exp(-zeta w_n 20 s) = exp(-31) at 0.2 s and exp(-12.6) at 0.5 s (at 2 s it would still be exp(-3.1)).
  const RotDMeasures r = rotd_measures(set, std::vector<double>{0.2, 0.5});
  // PGA: every whole-degree theta reaches A at a sample (w dt = 1 deg) once A is constant: round-off, 1e-14.
  for (double peak : r.pga_by_angle_m_s2) EXPECT_NEAR(peak, amp, 1e-14 * amp);
  EXPECT_NEAR(r.pga_m_s2.rotd50, amp, 1e-14 * amp);
  EXPECT_NEAR(r.pga_m_s2.rotd100, amp, 1e-14 * amp);
  // PSA: the steady response x_theta = X cos(wt - theta - phi) peaks at X for every theta; the residue of the slow
  // ramp's transient and the sampling of the maximum (a 1 deg step of the phase: 1 - cos 0.5 deg = 4e-5) leave
  // RotD100 / RotD50 - 1 below 1e-3.
  for (const RotDValue& psa : r.psa_m_s2) EXPECT_LT(psa.rotd100 / psa.rotd50 - 1.0, 1e-3) << psa.rotd100;
}

TEST(RotD, EveryAngleEqualsTheSpectrumOfTheProjectedRecord) {
  // Linearity: the rotated response built from the two components' responses equals the response spectrum of the
  // projected record (motion_set.hpp eq. M1), to round-off (1e-10 relative: two recurrences summed vs one).
  const auto h1 = sampled(0.01, 1500, [](double t) { return std::sin(7.0 * t) + 0.5 * std::sin(23.0 * t + 1.0); });
  const auto h2 = sampled(0.01, 1500, [](double t) { return 0.8 * std::cos(11.0 * t) - 0.3 * std::sin(3.0 * t); });
  const ComponentAzimuths az{20.0, 290.0};  // counter-clockwise pair: theta runs toward azimuth 20 - theta
  const MotionSet set = MotionSet::make(h1, &h2, az);
  const std::vector<double> periods{0.1, 0.4, 1.5};
  const RotDMeasures r = rotd_measures(set, periods);
  for (int k : {0, 17, 45, 90, 133, 179}) {
    const GroundMotion p = set.projected(az.first_deg - k);
    const ResponseSpectrum s = response_spectrum(p, periods);
    for (std::size_t j = 0; j < periods.size(); ++j) {
      EXPECT_NEAR(r.psa_by_angle_m_s2[j][k], s.psa_m_s2[j], 1e-10 * s.psa_m_s2[j]) << "theta " << k;
    }
    EXPECT_NEAR(r.pga_by_angle_m_s2[k], p.pga_m_s2(), 1e-14 * p.pga_m_s2()) << "theta " << k;
  }
  // The azimuth of RotD100 is first - theta for this handedness, as a direction in [0, 180).
  EXPECT_EQ(rotd_azimuth_deg(set, 30.0), 170.0);
}

// ---- pyrotd on a real pair ----

using test::venv_python;
using test::write_column;

TEST(RotDPeer, PyrotdOnTheCsmipPair) {
  if (!test::have_shared()) GTEST_SKIP() << "../shared is absent";
  if (!std::filesystem::exists(venv_python())) GTEST_SKIP() << ".venv-test is absent (scripts/test-venv.sh)";
  // A true pair: CSMIP 36456 (Coalinga 1983, Parkfield Fault Zone 14), channels 1 (90 deg) and 3 (0 deg), dt 0.02 s.
  // Channel 1 holds 3251 points and channel 3 3250 (SOURCES.md); pyrotd needs equal lengths, so channel 1 is
  // truncated to 3250 (its last sample, 65 s after the trigger, is in the coda).
  const auto path = test::shared_record("ce36456p_CE36456.V2");
  io::ReadOptions r1, r3;
  r1.channel = 1;
  r3.channel = 3;
  const GroundMotion c1 = io::read_motion(path, r1);
  const GroundMotion c3 = io::read_motion(path, r3);
  ASSERT_EQ(c1.size(), 3251u);
  ASSERT_EQ(c3.size(), 3250u);
  const double dt = c1.dt_s();
  const GroundMotion h1 = c1.trimmed(c1.start_time_s(), c1.time_s(3249));
  ASSERT_EQ(h1.size(), 3250u);
  // As in test_spectra's peer test: pyrotd sees the records linearly interpolated at dt/10 (the same piecewise-
  // linear functions) and 150 s of zeros (no wrap-around of its circular response); topple gets the same fine,
  // padded records, so both take maxima on the same dt/10 grid. pyrotd's band-limited interpolation of those
  // samples differs from their chords by about (pi dt / (10 T))^2 / 3 < 4e-4 at T >= 10 dt: 1e-3 relative.
  const std::vector<double> periods{0.2, 0.3, 0.5, 0.75, 1.0, 1.5, 2.0, 3.0, 4.0};
  constexpr int kUp = 10;
  constexpr double kPad = 150.0;
  const test::TempDir dir;
  write_column(dir.path() / "a.txt", h1.accel_m_s2());
  write_column(dir.path() / "b.txt", c3.accel_m_s2());
  const nlohmann::json peer = test::run_peer_script(
      "peer_rotd.py", fmt::format("'{}' '{}' {} '{}' {} {}", (dir.path() / "a.txt").string(),
                                  (dir.path() / "b.txt").string(), dt, nlohmann::json(periods).dump(), kUp, kPad));
  ASSERT_FALSE(peer.is_null());
  const auto fine = [&](const GroundMotion& m) { return test::upsampled_padded(m, kUp, kPad); };
  const GroundMotion f1 = fine(h1);
  const GroundMotion f3 = fine(c3);
  const MotionSet set = MotionSet::make(f1, &f3, ComponentAzimuths{90.0, 0.0});
  const RotDMeasures ours = rotd_measures(set, periods);
  double worst = 0.0;
  for (std::size_t p = 0; p < periods.size(); ++p) {
    for (const auto& [key, value] : {std::pair{"psa_rotd50", ours.psa_m_s2[p].rotd50},
                                     std::pair{"psa_rotd100", ours.psa_m_s2[p].rotd100}}) {
      const double theirs = peer[key][p].get<double>();
      const double rel = std::abs(value - theirs) / theirs;
      worst = std::max(worst, rel);
      EXPECT_LT(rel, 1e-3) << key << " T = " << periods[p] << ": topple " << value << ", pyrotd " << theirs;
    }
  }
  // PGA: the same peaks of the same samples (no oscillator, no FFT): round-off only, 1e-12 relative.
  const RotDMeasures raw = rotd_measures(MotionSet::make(h1, &c3, ComponentAzimuths{90.0, 0.0}), {});
  EXPECT_NEAR(raw.pga_m_s2.rotd50, peer["pga_rotd50"].get<double>(), 1e-12 * raw.pga_m_s2.rotd50);
  EXPECT_NEAR(raw.pga_m_s2.rotd100, peer["pga_rotd100"].get<double>(), 1e-12 * raw.pga_m_s2.rotd100);
  fmt::print("CSMIP 36456 pair: worst |topple - pyrotd| / pyrotd RotD PSA = {:.3g} over {} periods; RotD50 PGA {:.5f} "
             "g, RotD100 {:.5f} g\n",
             worst, periods.size(), raw.pga_m_s2.rotd50 / kStandardGravity, raw.pga_m_s2.rotd100 / kStandardGravity);
  RecordProperty("worst_relative_difference_pyrotd", fmt::format("{:.3g}", worst));
}

// ---- Synthetic pairs ----

SynthesisSetSpec pair_spec(std::uint64_t seed) {
  SynthesisSetSpec s;
  s.horizontal.pga_m_s2 = 0.3 * kStandardGravity;
  s.horizontal.predominant_frequency_hz = 3.0;
  s.horizontal.duration_s = 20.0;
  s.horizontal.dt_s = 0.01;
  s.horizontal.seed = seed;
  return s;
}

TEST(SynthesisSet, RotD50OfThePairIsTheRequestedPga) {
  const SynthesisSetSpec spec = pair_spec(7);
  const SynthesizedSet set = synthesize_set(spec);
  // Recomputed here through the motion set (not synthesis' own scaling path): equal to round-off, 1e-13 relative.
  const MotionSet ms = MotionSet::make(set.first, &set.second, spec.azimuths);
  const RotDMeasures r = rotd_measures(ms, {});
  EXPECT_NEAR(r.pga_m_s2.rotd50, spec.horizontal.pga_m_s2, 1e-13 * spec.horizontal.pga_m_s2);
  EXPECT_NEAR(set.rotd50_pga_m_s2, spec.horizontal.pga_m_s2, 1e-13 * spec.horizontal.pga_m_s2);
  EXPECT_GE(r.pga_m_s2.rotd100, r.pga_m_s2.rotd50);
  // Each component's own peak is within the pair's RotD100 and at least ... cos 45 of it (the bounds of a pair).
  for (const GroundMotion* m : {&set.first, &set.second}) EXPECT_LE(m->pga_m_s2(), r.pga_m_s2.rotd100 * (1 + 1e-15));
  // Vertical: V/H 2/3 of the RotD50 PGA, exactly as its own scaling sets it (1e-13 relative).
  ASSERT_TRUE(set.vertical.has_value());
  EXPECT_NEAR(set.vertical->pga_m_s2(), 2.0 / 3.0 * spec.horizontal.pga_m_s2, 1e-13 * spec.horizontal.pga_m_s2);
  EXPECT_TRUE(set.vertical->metadata().vertical);
  EXPECT_EQ(set.first.metadata().azimuth_deg, 90.0);
  EXPECT_EQ(set.second.metadata().azimuth_deg, 0.0);
  SynthesisSetSpec off = spec;
  off.vertical = false;
  EXPECT_FALSE(synthesize_set(off).vertical.has_value());
}

TEST(SynthesisSet, FirstComponentIsTheSingleMotionsShapeAndCoherenceHolds) {
  // The first component's noise is synthesize()'s (synthesis.hpp): the same shape, another scale factor. Checked
  // against the single-component generator, an independent path through the public API: ratio constant to 1e-12.
  SynthesisSetSpec spec = pair_spec(11);
  spec.horizontal.duration_s = 200.0;
  const GroundMotion single = synthesize(spec.horizontal);
  for (double rho : {0.0, 0.8, 1.0}) {
    spec.coherence = rho;
    const SynthesizedSet set = synthesize_set(spec);
    const auto a = set.first.accel_m_s2();
    const auto s = single.accel_m_s2();
    const std::size_t peak = static_cast<std::size_t>(std::max_element(s.begin(), s.end(), [](double x, double y) {
                                                        return std::abs(x) < std::abs(y);
                                                      }) - s.begin());
    const double ratio = a[peak] / s[peak];
    for (std::size_t i = 0; i < a.size(); i += 97) EXPECT_NEAR(a[i], ratio * s[i], 1e-12 * single.pga_m_s2());
    // Sample correlation of the two components. rho = 1: the same noise, the same motion (bit for bit). Otherwise
    // the filtered, enveloped components carry the noises' correlation rho; 200 s of a 3 Hz process has about
    // n_eff = 600 independent cycles, so the estimate's standard error is (1 - rho^2) / sqrt(n_eff) <= 0.04:
    // tolerance 0.12 (3 sigma).
    const auto b = set.second.accel_m_s2();
    if (rho == 1.0) {
      EXPECT_EQ(std::vector<double>(a.begin(), a.end()), std::vector<double>(b.begin(), b.end()));
      continue;
    }
    const double ab = std::inner_product(a.begin(), a.end(), b.begin(), 0.0);
    const double aa = std::inner_product(a.begin(), a.end(), a.begin(), 0.0);
    const double bb = std::inner_product(b.begin(), b.end(), b.begin(), 0.0);
    EXPECT_NEAR(ab / std::sqrt(aa * bb), rho, 0.12) << "rho " << rho;
  }
}

TEST(SynthesisSet, PortablePinnedNumbers) {
  // seed 2024, 0.3 g RotD50, 3 Hz, 20 s, dt 0.01 s, rho 0, V/H 2/3, f_v/f_h 1.5. Pinned from the first run, and
  // checked outside topple: `topple synth --components 3 --pga 0.3g --freq 3Hz --duration 20 --dt 0.01 --seed 2024`
  // wrote three CSVs that numpy read (.venv-test): its RotD50 of PGA (np.percentile(.., 50) of the peaks of
  // a1 cos t + a2 sin t, t = 0..179 deg, np.cos) is 0.29999999999999993 g and RotD100 0.34024781 g, the vertical's
  // peak 0.19999999999999996 g, and sample 500 x g gives these three values (H2 to the CSV's last digit); the
  // single-component generator gives H1's shape (test above). Exact equality: the generator is portable bit for bit
  // (synthesis.hpp), and so is rotd.cpp's angle table.
  SynthesisSetSpec spec = pair_spec(2024);
  const SynthesizedSet set = synthesize_set(spec);
  ASSERT_EQ(set.first.size(), 2001u);
  EXPECT_EQ(fmt::format("{:.17g}", set.first.accel_m_s2()[500]), "0.16589594385238426");
  EXPECT_EQ(fmt::format("{:.17g}", set.second.accel_m_s2()[500]), "-0.59577152828972557");
  EXPECT_EQ(fmt::format("{:.17g}", set.vertical->accel_m_s2()[500]), "-0.12665730368867878");
}

TEST(SynthesisSet, BadSpecsAreRefusedNamingTheField) {
  SynthesisSetSpec s = pair_spec(1);
  s.coherence = 1.5;
  expect_input_error([&] { return synthesize_set(s); }, "coherence", "[-1, 1]");
  s = pair_spec(1);
  s.vertical_pga_ratio = 0.0;
  expect_input_error([&] { return synthesize_set(s); }, "vertical_pga_ratio", "(0, 2]");
  s = pair_spec(1);
  s.vertical_frequency_ratio = 10.0;
  expect_input_error([&] { return synthesize_set(s); }, "vertical_frequency_ratio", "[0.5, 4]");
  s = pair_spec(1);
  s.azimuths = {0.0, 45.0};
  expect_input_error([&] { return synthesize_set(s); }, "azimuths", "perpendicular");
  s = pair_spec(1);
  s.horizontal.predominant_frequency_hz = 8.0;  // f_v = 12 Hz > 1 / (10 dt) = 10 Hz
  try {
    (void)synthesize_set(s);
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().field.rfind("vertical ", 0), 0u) << e.what();
  }
}

}  // namespace
}  // namespace topple
