#pragma once
// Reading accelerograms in the formats strong-motion agencies publish.
//
// Every reader converts to m/s^2 and seconds, fills RecordMetadata, and throws InputError naming the file, the
// 1-based line and the field for any problem (truncated data, NPTS mismatch, non-numeric token, non-positive dt,
// NaN/Inf, decreasing or repeated times, empty file, unknown units). Nothing is guessed: a plain file without units
// in its header needs ReadOptions::units.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "topple/motion/baseline.hpp"
#include "topple/motion/ground_motion.hpp"
#include "topple/core/units.hpp"

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
              ///< "accel_cm_s2", or a last comment line such as "# Time (s),Acceleration (g's)"); any number of
              ///< columns separated by tabs, blanks, commas or semicolons with ReadOptions::columns
};

/// One column of a plain file: by its 1-based number or by its header name (the name as the header writes it,
/// compared after trimming blanks, ignoring ASCII case; names may hold spaces).
struct ColumnRef {
  std::size_t number = 0;  ///< 1-based; 0 when chosen by name
  std::string name;        ///< when chosen by name
  [[nodiscard]] bool by_name() const noexcept { return number == 0; }
};

/// Which columns of a plain file hold the time and the acceleration (docs/formats.md, "Plain text").
struct ColumnChoice {
  std::optional<ColumnRef> time;  ///< none: the file has no time column, and ReadOptions::dt_s gives the step
  ColumnRef accel;
};

/// The separator of a plain file's fields.
enum class Separator {
  automatic,   ///< the header by its own content, the data by the first data line's: tab if it holds one, else
               ///< semicolon, else comma, else blanks
  whitespace,  ///< runs of blanks and tabs
  tab,
  comma,
  semicolon,
};

/// "TIME,ACCEL" (each a 1-based number or a header name: "1,2", "Time (s),Table Acc (g)"), ",ACCEL" or "accel=ACCEL"
/// (no time column), or "time=TIME,accel=ACCEL". A part made of digits only is a number. Throws InputError naming
/// `field` for an empty choice, a number < 1, or the same column twice (by number, or the same name).
[[nodiscard]] ColumnChoice parse_columns(std::string_view text, const std::string& field = "--columns");

/// "auto", "whitespace" (or "space"), "tab", "comma", "semicolon"; InputError naming `field` otherwise.
[[nodiscard]] Separator parse_separator(std::string_view text, const std::string& field = "--separator");

struct ReadOptions {
  Format format = Format::automatic;
  /// 1-based channel for multi-channel files (CSMIP V2, COSMOS files holding several acceleration channels); required
  /// there when the file holds more than one. Any other value than 1 is an error for a single-channel file.
  std::optional<int> channel;
  /// Acceleration unit of the file's values ("g", "m/s2", "cm/s2", "gal"). Required for a plain file whose header
  /// names no unit. For a file that states its unit (every agency format, a plain header such as "accel_g") it may
  /// be given only when it agrees with the file (gal = cm/s2); a conflict is an InputError naming --units.
  std::string units;
  /// Time step, s. Required for a one-column plain file; for a file that states its time step (every agency
  /// format) it may be given only when it agrees to 1e-6 relative; a conflict is an InputError naming --dt. An error
  /// for a plain file with a time column.
  std::optional<double> dt_s;
  /// g used to convert values in g to m/s^2.
  double g_m_s2 = kStandardGravity;
  /// Plain files: the time and acceleration columns. Without it a plain file holds one column (acceleration) or two
  /// (time, acceleration), as before; with it any number, the others ignored (never parsed: they may hold text),
  /// every data row having as many fields as the first. The unit comes from the chosen column's header name
  /// ("Table Acc (g)", "acc [m/s2]", "accel_g") or `units`. An error for the other formats.
  std::optional<ColumnChoice> columns;
  /// Plain files: how fields are separated. An error for the other formats unless automatic.
  Separator separator = Separator::automatic;
  /// Offset removal applied to the record as read (every format): none by default (the record bit for bit).
  Baseline baseline;
};

/// Limits on every text file topple reads (records, survey and sweep files), README "Limits". Records of real
/// agencies are at most a few MB (a 300 s K-NET record is 0.3 MB, a 42000-point COSMOS V2c 0.7 MB; one hour of
/// one-column text at 1 kHz about 50 MB), and their lines are shorter than 200 characters.
inline constexpr std::uintmax_t kMaxInputFileBytes = std::uintmax_t{64} << 20;  ///< 64 MiB
inline constexpr std::size_t kMaxInputLineBytes = std::size_t{1} << 20;         ///< 1 MiB

/// The whole content of a text input file. Throws InputError naming the file (and `what` it should be, e.g.
/// "record", "survey", "sweep") for something that is not a regular file (a directory, a device such as /dev/zero,
/// a FIFO), a file that cannot be opened or read, a file over kMaxInputFileBytes, or a line over
/// kMaxInputLineBytes. Every reader of topple goes through it, so that no input can make memory grow without bound.
[[nodiscard]] std::string read_input_file(const std::filesystem::path& path, std::string_view what);

/// The size and line-length checks of read_input_file on text already in memory; `name` is used in messages.
void check_input_text(std::string_view content, const std::string& name);

/// Reads one ground-motion component from `path`.
[[nodiscard]] GroundMotion read_motion(const std::filesystem::path& path, const ReadOptions& options = {});

/// Same as read_motion on text already in memory; `name` is used in error messages (and is what the fuzz targets call).
[[nodiscard]] GroundMotion parse_motion(std::string_view content, const std::string& name,
                                        const ReadOptions& options = {});

/// A channel's orientation read from its component text (RecordMetadata::component) as the agency formats write it
/// (docs/formats.md, "Orientation"):
///   "N-S", "NS" -> azimuth 0; "E-W", "EW" -> 90 (K-NET/KiK-net, positive north and east; KiK-net's "N-S (surface,
///   Dir. 4)" too); "U-D", "UD", "UP", "VERT", "Z" -> vertical (positive up);
///   "90 DEG", "360 deg", "90" (CSMIP V2, COSMOS V2 text line 9 "1: 90 deg" after its channel number, USGS SMC)
///   -> that azimuth mod 360;
///   a SEED channel code ending in N, E or Z ("HNE", "BNZ"; ESM STREAM, the COSMOS End-of-data line) -> 0, 90,
///   vertical (SEED: N and E within 5 deg of north and east; 1, 2 and 3 are unoriented and give nothing).
/// Anything else ("DOWN", "FN", "-E", "HN1", "") gives nothing: no guess.
struct ComponentOrientation {
  std::optional<double> azimuth_deg;  ///< degrees clockwise from north in [0, 360)
  bool vertical = false;              ///< the vertical channel, positive up
};
[[nodiscard]] ComponentOrientation orientation_from_component(std::string_view component);

/// The format of `content`, judged from its text. Returns Format::plain when nothing more specific matches.
[[nodiscard]] Format detect_format(std::string_view content);

/// Stable lower-case name ("peer-at2", "cosmos-v2", "csmip-v2", "knet", "usgs-smc", "esm", "plain").
[[nodiscard]] std::string_view format_name(Format format);

/// Inverse of format_name (also accepts "auto"); throws InputError naming `field` for an unknown name.
[[nodiscard]] Format parse_format_name(std::string_view name, const std::string& field = "--format");

}  // namespace topple::io
