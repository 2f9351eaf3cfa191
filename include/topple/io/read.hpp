#pragma once
// Reading accelerograms in the formats strong-motion agencies publish.
//
// Every reader converts to m/s^2 and seconds, fills RecordMetadata, and throws InputError naming the file, the
// 1-based line and the field for any problem (truncated data, NPTS mismatch, non-numeric token, non-positive dt,
// NaN/Inf, decreasing or repeated times, empty file, unknown units). Nothing is guessed: a plain file without units
// in its header needs ReadOptions::units.
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "topple/ground_motion.hpp"
#include "topple/units.hpp"

namespace topple::io {

enum class Format {
  automatic,  ///< detect from content (never from the file name)
  peer_at2,   ///< PEER NGA / PE&A .AT2 (values in g; NGA-West2 and older header forms)
  cosmos_v2,  ///< COSMOS V2 / V2c processed acceleration
  csmip_v2,   ///< CSMIP / CDMG "DMG" V2 (several channels in one file)
  knet,       ///< NIED K-NET / KiK-net ASCII (counts x scale factor, gal; record mean removed)
  usgs_smc,   ///< USGS SMC corrected accelerogram (fixed-width values)
  esm,        ///< ESM / ITACA ASCII ("KEY: value" header)
  plain,      ///< plain text: one column with a given dt, or time/acceleration columns (CSV or whitespace);
              ///< '#' comments, optional UTF-8 BOM, optional header naming the columns with units ("time_s,accel_g",
              ///< "accel_cm_s2", or a last comment line such as "# Time (s),Acceleration (g's)")
};

struct ReadOptions {
  Format format = Format::automatic;
  /// 1-based channel for multi-channel files (CSMIP V2, COSMOS files holding several acceleration channels); required
  /// there when the file holds more than one. Any other value than 1 is an error for a single-channel file.
  std::optional<int> channel;
  /// Acceleration unit of a plain file's values ("g", "m/s2", "cm/s2", "gal"); overrides a unit named in its
  /// header (e.g. "accel_g"). Ignored for self-describing formats.
  std::string units;
  /// Time step of a one-column plain file, s (an error for a file that has a time column).
  std::optional<double> dt_s;
  /// g used to convert values in g to m/s^2.
  double g_m_s2 = kStandardGravity;
};

/// Reads one ground-motion component from `path`.
[[nodiscard]] GroundMotion read_motion(const std::filesystem::path& path, const ReadOptions& options = {});

/// Same as read_motion on text already in memory; `name` is used in error messages (and is what the fuzz targets call).
[[nodiscard]] GroundMotion parse_motion(std::string_view content, const std::string& name,
                                        const ReadOptions& options = {});

/// The format of `content`, judged from its text. Returns Format::plain when nothing more specific matches.
[[nodiscard]] Format detect_format(std::string_view content);

/// Stable lower-case name ("peer-at2", "cosmos-v2", "csmip-v2", "knet", "usgs-smc", "esm", "plain").
[[nodiscard]] std::string_view format_name(Format format);

/// Inverse of format_name (also accepts "auto"); throws InputError naming `field` for an unknown name.
[[nodiscard]] Format parse_format_name(std::string_view name, const std::string& field = "--format");

}  // namespace topple::io
