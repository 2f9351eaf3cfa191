// Ground-motion readers: format names, detection from content, dispatch, and the plain-text reader.
// The agency formats live one per file beside this one (peer_at2.cpp, cosmos_v2.cpp, csmip_v2.cpp, knet.cpp,
// usgs_smc.cpp, esm.cpp); the layouts they follow are summarised in ../shared/records/SOURCES.md.
#include "topple/io/read.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <system_error>

#include <fmt/format.h>

#include "io/text_lines.hpp"
#include "topple/core/error.hpp"
#include "topple/core/units.hpp"
#include "topple/core/enum_names.hpp"

namespace topple::io {

constexpr std::array<EnumName<Format>, 8> kFormatNames{{
    {Format::automatic, "auto"},
    {Format::peer_at2, "peer-at2"},
    {Format::cosmos_v2, "cosmos-v2"},
    {Format::csmip_v2, "csmip-v2"},
    {Format::knet, "knet"},
    {Format::usgs_smc, "usgs-smc"},
    {Format::esm, "esm"},
    {Format::plain, "plain"},
}};

std::string_view format_name(Format format) { return enum_name(kFormatNames, format); }

Format parse_format_name(std::string_view name, const std::string& field) {
  for (Format f : {Format::automatic, Format::peer_at2, Format::cosmos_v2, Format::csmip_v2, Format::knet,
                   Format::usgs_smc, Format::esm, Format::plain}) {
    if (name == format_name(f)) return f;
  }
  throw parameter_error(field, "unknown format '" + std::string(name) +
                                   "' (known: auto, peer-at2, cosmos-v2, csmip-v2, knet, usgs-smc, esm, plain)");
}

namespace {

std::string_view trim_blanks(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

/// Parts of a --columns text split at commas outside double quotes, each trimmed and unquoted.
std::vector<std::string> column_parts(std::string_view text, const std::string& field) {
  std::vector<std::string> parts(1);
  bool quoted = false;
  for (char c : text) {
    if (c == '"') {
      quoted = !quoted;
    } else if (c == ',' && !quoted) {
      parts.emplace_back();
    } else {
      parts.back() += c;
    }
  }
  if (quoted) throw parameter_error(field, fmt::format("unbalanced double quote in '{}'", text));
  for (std::string& p : parts) p = std::string(trim_blanks(p));
  return parts;
}

/// A part of a --columns text: digits only -> a 1-based number, else a header name.
ColumnRef column_ref(const std::string& part, const std::string& field, std::string_view role) {
  ColumnRef ref;
  if (!part.empty() && std::all_of(part.begin(), part.end(), [](char c) { return c >= '0' && c <= '9'; })) {
    std::size_t n = 0;
    const auto [ptr, ec] = std::from_chars(part.data(), part.data() + part.size(), n);
    if (ec != std::errc{} || n < 1 || n > 100000) {
      throw parameter_error(field, fmt::format("the {} column number must be 1 or more, got {}", role, part));
    }
    ref.number = n;
  } else {
    ref.name = part;
  }
  return ref;
}

bool same_column(const ColumnRef& a, const ColumnRef& b) {
  if (a.by_name() != b.by_name()) return false;
  if (!a.by_name()) return a.number == b.number;
  return detail::to_lower(a.name) == detail::to_lower(b.name);
}

}  // namespace

ColumnChoice parse_columns(std::string_view text, const std::string& field) {
  const auto grammar = [&](const std::string& problem) {
    return parameter_error(field, fmt::format("{}: give TIME,ACCEL (column numbers from 1 or header names, e.g. 1,2 "
                                              "or \"Time (s),Table Acc (g)\"), ,ACCEL or accel=ACCEL without a time "
                                              "column, or time=TIME,accel=ACCEL; got '{}'",
                                              problem, text));
  };
  const std::vector<std::string> parts = column_parts(text, field);
  std::optional<std::string> time_part;
  std::optional<std::string> accel_part;
  const auto keyed = [](const std::string& p, std::string_view key) {
    return p.size() > key.size() && p[key.size()] == '=' && detail::starts_with_ci(p, key);
  };
  if (std::any_of(parts.begin(), parts.end(), [&](const std::string& p) { return keyed(p, "time") || keyed(p, "accel"); })) {
    for (const std::string& p : parts) {
      const bool is_time = keyed(p, "time");
      if (!is_time && !keyed(p, "accel")) throw grammar(fmt::format("'{}' is not time=... or accel=...", p));
      std::optional<std::string>& slot = is_time ? time_part : accel_part;
      if (slot) throw grammar(fmt::format("{} is given twice", is_time ? "time" : "accel"));
      slot = std::string(trim_blanks(std::string_view(p).substr(is_time ? 5 : 6)));
    }
    if (time_part && time_part->empty()) time_part.reset();
  } else {
    if (parts.size() != 2) throw grammar(fmt::format("{} part{}", parts.size(), parts.size() == 1 ? "" : "s"));
    if (!parts[0].empty()) time_part = parts[0];
    accel_part = parts[1];
  }
  if (!accel_part || accel_part->empty()) throw grammar("no acceleration column");
  ColumnChoice choice;
  choice.accel = column_ref(*accel_part, field, "acceleration");
  if (time_part) {
    choice.time = column_ref(*time_part, field, "time");
    if (same_column(*choice.time, choice.accel)) {
      throw parameter_error(field, fmt::format("the time and the acceleration are the same column '{}'", *accel_part));
    }
  }
  return choice;
}

Separator parse_separator(std::string_view text, const std::string& field) {
  if (text == "auto") return Separator::automatic;
  if (text == "whitespace" || text == "space") return Separator::whitespace;
  if (text == "tab") return Separator::tab;
  if (text == "comma") return Separator::comma;
  if (text == "semicolon") return Separator::semicolon;
  throw parameter_error(field, fmt::format("unknown separator '{}' (known: auto, whitespace, tab, comma, semicolon)",
                                           text));
}

ComponentOrientation orientation_from_component(std::string_view component) {
  // Upper case, without what a parenthesis adds ("N-S (surface, Dir. 4)") and surrounding blanks.
  std::string c;
  for (char ch : component.substr(0, component.find('('))) {
    c += static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
  }
  // COSMOS text line 9 names the channel "1: 90 deg": what follows the channel number.
  if (const auto colon = c.find(':'); colon != std::string::npos) c = c.substr(colon + 1);
  const auto first = c.find_first_not_of(" \t");
  if (first == std::string::npos) return {};
  c = c.substr(first, c.find_last_not_of(" \t") - first + 1);
  ComponentOrientation o;
  if (c == "N-S" || c == "NS") {
    o.azimuth_deg = 0.0;
  } else if (c == "E-W" || c == "EW") {
    o.azimuth_deg = 90.0;
  } else if (c == "U-D" || c == "UD" || c == "UP" || c == "VERT" || c == "Z") {
    o.vertical = true;
  } else if (c.size() == 3 && std::isalpha(static_cast<unsigned char>(c[0])) &&
             std::isalpha(static_cast<unsigned char>(c[1])) && std::string_view("NEZ").find(c[2]) != std::string::npos) {
    // A SEED channel code: band, instrument, orientation (N, E within 5 deg of north and east; Z up).
    if (c[2] == 'Z') o.vertical = true;
    else o.azimuth_deg = c[2] == 'N' ? 0.0 : 90.0;
  } else {
    // "90 DEG", "360 deg", "90": a whole number of degrees, optionally followed by DEG.
    std::string_view number(c);
    if (number.ends_with("DEG")) number.remove_suffix(3);
    while (!number.empty() && number.back() == ' ') number.remove_suffix(1);
    int deg = 0;
    const auto [ptr, ec] = std::from_chars(number.data(), number.data() + number.size(), deg);
    if (!number.empty() && ec == std::errc{} && ptr == number.data() + number.size() && deg >= 0 && deg <= 360) {
      o.azimuth_deg = static_cast<double>(deg % 360);
    }
  }
  return o;
}

Format detect_format(std::string_view content) {
  // Every agency format announces itself in its first lines; only those are looked at, so detection costs nothing
  // on large files. The order matters only where signatures could overlap: an SMC first line ("2 CORRECTED
  // ACCELEROGRAM") also names a corrected accelerogram, as CSMIP V2 does, so the stronger CSMIP data-section
  // signature is tried first.
  const std::vector<detail::Line> head = detail::split_lines(content, 120);
  if (detail::looks_like_cosmos_v2(head)) return Format::cosmos_v2;
  if (detail::looks_like_csmip_v2(head)) return Format::csmip_v2;
  if (detail::looks_like_usgs_smc(head)) return Format::usgs_smc;
  if (detail::looks_like_knet(head)) return Format::knet;
  if (detail::looks_like_esm(head)) return Format::esm;
  if (detail::looks_like_peer_at2(head)) return Format::peer_at2;
  return Format::plain;
}

GroundMotion parse_motion(std::string_view content, const std::string& name, const ReadOptions& options) {
  if (!(options.g_m_s2 > 0.0) || !std::isfinite(options.g_m_s2)) {
    throw parameter_error("g", fmt::format("g must be positive and finite, got {}", options.g_m_s2));
  }
  check_input_text(content, name);
  const Format format = options.format == Format::automatic ? detect_format(content) : options.format;
  const detail::Text text(content, name);
  if (options.channel && *options.channel < 1) {
    text.fail_file("--channel", fmt::format("channels are numbered from 1, got {}", *options.channel));
  }
  if (options.channel && *options.channel != 1 && format != Format::csmip_v2 && format != Format::cosmos_v2) {
    text.fail_file("--channel", fmt::format("a {} file holds one channel; there is no channel {}",
                                            format_name(format), *options.channel));
  }
  if (format != Format::plain && (options.columns || options.separator != Separator::automatic)) {
    text.fail_file(options.columns ? "--columns" : "--separator",
                   fmt::format("a {} file has its own layout; --columns and --separator apply to plain files",
                               format_name(format)));
  }
  if (text.empty() || std::all_of(text.lines().begin(), text.lines().end(),
                                  [](const detail::Line& l) { return detail::is_blank(l.text); })) {
    text.fail_file("", "the file is empty");
  }
  GroundMotion motion = [&] {
    try {
      GroundMotion read = [&] {
        switch (format) {
          case Format::peer_at2: return detail::read_peer_at2(text, options);
          case Format::cosmos_v2: return detail::read_cosmos_v2(text, options);
          case Format::csmip_v2: return detail::read_csmip_v2(text, options);
          case Format::knet: return detail::read_knet(text, options);
          case Format::usgs_smc: return detail::read_usgs_smc(text, options);
          case Format::esm: return detail::read_esm(text, options);
          case Format::plain:
          case Format::automatic: break;
        }
        return detail::read_plain(text, options);
      }();
      // The offset removal asked for (none by default: the record as read, bit for bit; motion/baseline.hpp).
      return remove_baseline(read, options.baseline, "--baseline");
    } catch (const InputError& e) {
      // The readers check the limits of GroundMotion themselves, at the line concerned; a check that only the
      // constructor makes (or the baseline's) still names the file.
      if (!e.where().file.empty()) throw;
      text.fail_file(e.where().field, e.problem());
    }
  }();
  RecordMetadata meta = motion.metadata();
  meta.format = std::string(format_name(format));
  meta.source_file = name;
  // The formats whose headers state the channel's orientation (a PEER AT2 component such as "180" is a naming
  // convention of the database, sometimes a rotated "FN"; a plain file states nothing).
  if (format == Format::cosmos_v2 || format == Format::csmip_v2 || format == Format::knet ||
      format == Format::usgs_smc || format == Format::esm) {
    const ComponentOrientation o = orientation_from_component(meta.component);
    meta.azimuth_deg = o.azimuth_deg;
    meta.vertical = o.vertical;
  }
  motion.set_metadata(std::move(meta));
  return motion;
}

void check_input_text(std::string_view content, const std::string& name) {
  const auto fail = [&](std::optional<std::size_t> line, const std::string& problem) {
    throw InputError(InputLocation{.file = name, .line = line, .field = {}}, problem);
  };
  if (content.size() > kMaxInputFileBytes) {
    fail(std::nullopt, fmt::format("the file is larger than the limit of {} MiB of an input file",
                                   kMaxInputFileBytes >> 20));
  }
  std::size_t line = 1;
  for (std::size_t begin = 0; begin < content.size(); ++line) {
    const std::size_t nl = content.find('\n', begin);
    const std::size_t end = nl == std::string_view::npos ? content.size() : nl;
    if (end - begin > kMaxInputLineBytes) {
      fail(line, fmt::format("the line is longer than the limit of {} KiB of a line (is this a text file?)",
                             kMaxInputLineBytes >> 10));
    }
    if (nl == std::string_view::npos) break;
    begin = nl + 1;
  }
}

std::string read_input_file(const std::filesystem::path& path, std::string_view what) {
  namespace fs = std::filesystem;
  const std::string name = path.string();
  const auto fail = [&](const std::string& problem) {
    throw InputError(InputLocation{.file = name, .line = {}, .field = {}}, problem);
  };
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);  // follows links: a link to /dev/zero is a device
  if (!fs::exists(status)) fail(fmt::format("cannot open the {} file: it does not exist", what));
  if (ec) fail(fmt::format("cannot open the {} file: {}", what, ec.message()));
  if (fs::is_directory(status)) fail(fmt::format("is a directory, not a {} file", what));
  if (!fs::is_regular_file(status)) {
    const char* kind = fs::is_character_file(status) ? "a character device"
                       : fs::is_block_file(status)   ? "a block device"
                       : fs::is_fifo(status)         ? "a FIFO (named pipe)"
                       : fs::is_socket(status)       ? "a socket"
                                                     : "not a regular file";
    fail(fmt::format("is {}, not a {} file (only regular files are read)", kind, what));
  }
  const std::uintmax_t size = fs::file_size(path, ec);
  if (!ec && size > kMaxInputFileBytes) {
    fail(fmt::format("the file holds {} bytes, more than the limit of {} MiB of an input file", size,
                     kMaxInputFileBytes >> 20));
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(fmt::format("cannot open the {} file", what));
  // Read at most one byte past the limit: a file that grows while it is read is still bounded.
  std::string text(static_cast<std::size_t>(std::min<std::uintmax_t>(ec ? 0 : size, kMaxInputFileBytes)), '\0');
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  text.resize(static_cast<std::size_t>(in.gcount()));
  if (in.bad()) fail(fmt::format("cannot read the {} file", what));
  if (in) {
    char buffer[65536];
    while (text.size() <= kMaxInputFileBytes && in.read(buffer, sizeof buffer).gcount() > 0) {
      text.append(buffer, static_cast<std::size_t>(in.gcount()));
    }
    if (in.bad()) fail(fmt::format("cannot read the {} file", what));
  }
  check_input_text(text, name);
  return text;
}

GroundMotion read_motion(const std::filesystem::path& path, const ReadOptions& options) {
  return parse_motion(read_input_file(path, "record"), path.string(), options);
}

// ---------------------------------------------------------------------------------------------------------------
// Plain text
//
// One column of accelerations at a given dt, or time/acceleration pairs separated by a comma or by blanks. Lines
// starting with '#' are comments. An optional header line names the columns, with units: "time_s,accel_g",
// "time_s,accel_m_s2", "accel_cm_s2", "Time (s),Acceleration (g's)". The pySLAMMER files carry that header as their
// last comment line ("# Time (s),Acceleration (g's)"), so a comment right before the data that names a time and an
// acceleration column, one per data column, counts as the header too. Without a unit in the header or
// ReadOptions::units the reader refuses the file rather than assume g.
// ---------------------------------------------------------------------------------------------------------------
namespace detail {
namespace {

struct Column {
  std::string name;      ///< as written
  std::string quantity;  ///< lower case, without the unit
  std::string unit;      ///< lower case, "" when none is named
  bool unit_in_brackets = false;  ///< "(g)", "[m/s2]": stated as a unit; "_g" is a suffix that may be one
};

/// "accel_g" -> {accel, g}; "accel_m_s2" -> {accel, m/s2}; "Acceleration (g's)" -> {acceleration, g};
/// "time [s]" -> {time, s}.
Column parse_column(std::string_view raw) {
  Column c;
  c.name = std::string(trim(raw));
  std::string s = to_lower(c.name);
  const std::size_t bracket = s.find_first_of("([");
  if (bracket != std::string::npos) {
    const std::size_t close = s.find_first_of(")]", bracket);
    c.unit = std::string(trim(std::string_view(s).substr(bracket + 1, close == std::string::npos
                                                                          ? std::string::npos
                                                                          : close - bracket - 1)));
    c.quantity = std::string(trim(std::string_view(s).substr(0, bracket)));
    c.unit_in_brackets = true;
  } else if (const std::size_t us = s.find('_'); us != std::string::npos) {
    c.quantity = s.substr(0, us);
    c.unit = s.substr(us + 1);
    // "m_s2" -> "m/s2": in an identifier the first underscore of the unit stands for the slash.
    if (const std::size_t u2 = c.unit.find('_'); u2 != std::string::npos) c.unit[u2] = '/';
  } else {
    c.quantity = s;
  }
  if (c.unit.ends_with("'s")) c.unit.resize(c.unit.size() - 2);  // "g's"
  c.unit = std::string(trim(c.unit));
  return c;
}

bool is_time_column(const Column& c) { return c.quantity == "t" || c.quantity.starts_with("time"); }
bool is_accel_column(const Column& c) {
  return c.quantity == "a" || c.quantity == "ag" || c.quantity.starts_with("acc") ||
         c.quantity.find("accel") != std::string::npos;
}

/// Fields separated by `sep`, each trimmed of blanks. Trailing empty fields (a trailing separator) are dropped; an
/// empty field elsewhere is kept so that the caller can refuse it.
std::vector<std::string_view> split_at(std::string_view s, char sep) {
  std::vector<std::string_view> fields;
  std::size_t begin = 0;
  while (true) {
    const std::size_t at = s.find(sep, begin);
    fields.push_back(trim(s.substr(begin, at == std::string_view::npos ? std::string_view::npos : at - begin)));
    if (at == std::string_view::npos) break;
    begin = at + 1;
  }
  while (!fields.empty() && fields.back().empty()) fields.pop_back();
  return fields;
}

/// The separator of a file, judged from its first non-comment line (its header, or its first data line).
Separator detect_separator(std::string_view s) {
  if (s.find('\t') != std::string_view::npos) return Separator::tab;
  if (s.find(';') != std::string_view::npos) return Separator::semicolon;
  if (s.find(',') != std::string_view::npos) return Separator::comma;
  return Separator::whitespace;
}

/// Fields of a line. `automatic` is the rule of the files before separators could be chosen, kept for comments:
/// comma-separated when the line has a comma, else blank-separated. A tab-separated file's line without a tab is
/// split at blanks (data aligned with spaces under a tab-separated header).
std::vector<std::string_view> split_fields(std::string_view s, Separator sep) {
  switch (sep) {
    case Separator::whitespace: return split_whitespace(s);
    case Separator::tab: return s.find('\t') == std::string_view::npos ? split_whitespace(s) : split_at(s, '\t');
    case Separator::comma: return split_at(s, ',');
    case Separator::semicolon: return split_at(s, ';');
    case Separator::automatic: break;
  }
  if (s.find(',') == std::string_view::npos) return split_whitespace(s);
  return split_at(s, ',');
}

std::string_view comment_body(std::string_view s) {
  s = trim(s);
  if (s.starts_with('#')) s.remove_prefix(1);
  return trim(s);
}

struct Header {
  std::vector<Column> columns;
  std::size_t line = 0;
  bool from_comment = false;
};

/// The header's names, quoted, for messages.
std::string header_names(const Header& h) {
  std::string out;
  for (std::size_t k = 0; k < h.columns.size(); ++k) {
    out += fmt::format("{}{} {}", k == 0 ? "" : ", ", k + 1, detail::quoted(h.columns[k].name));
  }
  return out;
}

/// A commented line taken as the header only when it names what the data columns are (without a column choice), or
/// when it has one name per data column, not all of them numbers (with one).
std::optional<Header> header_from_comment(const Line& comment, std::size_t data_columns, Separator sep,
                                          bool chosen) {
  // The comment's own separator unless one is forced (a tab-separated header over blank-separated data).
  const std::string_view body = comment_body(comment.text);
  const Separator comment_sep = sep == Separator::automatic ? detect_separator(body) : sep;
  const auto fields = split_fields(body, comment_sep);
  if (fields.size() != data_columns) return std::nullopt;
  Header h;
  h.line = comment.number;
  h.from_comment = true;
  for (std::string_view f : fields) h.columns.push_back(parse_column(f));
  // With a column choice any names do, but only from a comment split at tabs, commas or semicolons: a blank-separated
  // comment is more often a sentence ("# test 3") than a row of names.
  if (chosen && comment_sep != Separator::whitespace) {
    const bool names = std::any_of(fields.begin(), fields.end(), [](std::string_view f) { return !try_number(f); });
    const bool complete = std::none_of(fields.begin(), fields.end(), [](std::string_view f) { return f.empty(); });
    if (!names || !complete) return std::nullopt;
    return h;
  }
  const bool names_columns = data_columns == 2 ? is_time_column(h.columns[0]) && is_accel_column(h.columns[1])
                                               : is_accel_column(h.columns[0]);
  if (!names_columns) return std::nullopt;
  return h;
}

/// "Time Series: Kobe, Japan 1995 - TAK-090" (pySLAMMER) -> event, station, component.
void metadata_from_title(std::string_view comment, RecordMetadata& meta) {
  std::string_view s = comment_body(comment);
  if (!starts_with_ci(s, "time series:")) return;
  s = trim(s.substr(12));
  while (!s.empty() && s.back() == ',') s.remove_suffix(1);
  const std::size_t dash = s.rfind(" - ");
  if (dash == std::string_view::npos) {
    meta.event = std::string(s);
    return;
  }
  meta.event = std::string(trim(s.substr(0, dash)));
  const std::string_view rest = trim(s.substr(dash + 3));
  const std::size_t hyphen = rest.rfind('-');
  if (hyphen == std::string_view::npos || hyphen == 0) {
    meta.station = std::string(rest);
  } else {
    meta.station = std::string(rest.substr(0, hyphen));
    meta.component = std::string(rest.substr(hyphen + 1));
  }
}

/// A plain file's lines: its header (a line of column names, or the last comment before the data naming them), its
/// first comment (a title), which columns hold the time and the acceleration, and their samples.
struct PlainData {
  std::optional<Header> header;
  std::optional<Line> first_comment;
  std::size_t columns = 0;
  std::size_t first_data_line = 0;
  std::optional<std::size_t> time_index;  ///< 0-based; none: no time column
  std::size_t accel_index = 0;
  std::string time_field = "time";
  std::string accel_field = "acceleration";
  Samples times;
  Samples accels;
};

/// The 0-based index of the column `ref` (the `role` column of a --columns choice) in a file of `d.columns`
/// columns, refusing a number beyond them, a name without a header, and a name the header does not hold (or holds
/// twice), listing the header's names.
std::size_t resolve_column(const Text& text, const PlainData& d, const ColumnRef& ref, std::string_view role) {
  const std::string names = d.header ? fmt::format("; the header (line {}) names {}", d.header->line,
                                                   header_names(*d.header))
                                     : std::string();
  if (!ref.by_name()) {
    if (ref.number > d.columns) {
      text.fail(d.first_data_line, "--columns",
                fmt::format("the {} column is column {}, but the data has {} column{}{}", role, ref.number,
                            d.columns, d.columns == 1 ? "" : "s", names));
    }
    return ref.number - 1;
  }
  if (!d.header) {
    text.fail_file("--columns", fmt::format("the {} column is named {}, but no header line names the file's columns: "
                                            "choose it by number (e.g. --columns 1,2)",
                                            role, detail::quoted(ref.name)));
  }
  const std::string wanted = to_lower(trim(ref.name));
  std::optional<std::size_t> found;
  for (std::size_t k = 0; k < d.header->columns.size(); ++k) {
    if (to_lower(d.header->columns[k].name) != wanted) continue;
    if (found) {
      text.fail(d.header->line, "--columns",
                fmt::format("the header names columns {} and {} {}: choose the {} column by number", *found + 1,
                            k + 1, detail::quoted(ref.name), role));
    }
    found = k;
  }
  if (!found) {
    text.fail(d.header->line, "--columns",
              fmt::format("no column named {} (the {} column){}", detail::quoted(ref.name), role, names));
  }
  return *found;
}

/// With a column choice: the header must name every data column; then the chosen columns are resolved.
void choose_columns(const Text& text, PlainData& d, const ColumnChoice& choice) {
  if (d.header && d.header->columns.size() != d.columns) {
    text.fail(d.header->line, "header",
              fmt::format("the header names {} column{} but the data (line {}) has {}", d.header->columns.size(),
                          d.header->columns.size() == 1 ? "" : "s", d.first_data_line, d.columns));
  }
  const auto field_of = [&](std::size_t k) {
    return d.header ? d.header->columns[k].name : fmt::format("column {}", k + 1);
  };
  d.accel_index = resolve_column(text, d, choice.accel, "acceleration");
  d.accel_field = field_of(d.accel_index);
  if (choice.time) {
    d.time_index = resolve_column(text, d, *choice.time, "time");
    if (*d.time_index == d.accel_index) {
      text.fail_file("--columns", fmt::format("the time and the acceleration are the same column ({} {})",
                                              d.accel_index + 1, detail::quoted(d.accel_field)));
    }
    d.time_field = field_of(*d.time_index);
  }
}

PlainData scan_plain(const Text& text, const ReadOptions& options) {
  PlainData d;
  // Automatic: the header is split by its own separator and the data by the first data line's, as before separators
  // could be chosen ("time_s, accel_g" over "0 0.1" read then and reads now).
  Separator sep = options.separator;
  const bool chosen = options.columns.has_value();
  std::optional<Line> last_comment;
  for (const Line& line : text.lines()) {
    const std::string_view s = trim(line.text);
    if (s.empty()) continue;
    if (s.starts_with('#')) {
      if (d.columns == 0) {
        last_comment = line;
        if (!d.first_comment) d.first_comment = line;
      }
      continue;
    }
    const Separator line_sep = sep == Separator::automatic ? detect_separator(s) : sep;
    const auto fields = split_fields(s, line_sep);
    if (fields.empty()) {
      text.fail(line.number, "", fmt::format("no values on the line {}", detail::quoted(s)));
    }
    if (d.columns == 0 && !d.header && !try_number(fields.front())) {
      // The first non-comment line that does not start with a number names the columns.
      Header h;
      h.line = line.number;
      for (std::size_t k = 0; k < fields.size(); ++k) {
        if (fields[k].empty()) {
          text.fail(line.number, "header", fmt::format("empty name of column {} in the header", k + 1));
        }
        h.columns.push_back(parse_column(fields[k]));
      }
      d.header = std::move(h);
      continue;
    }
    if (d.columns == 0) {
      sep = line_sep;  // the data's separator, from its first line
      d.columns = fields.size();
      d.first_data_line = line.number;
      if (!d.header && last_comment) d.header = header_from_comment(*last_comment, d.columns, options.separator, chosen);
      if (chosen) {
        choose_columns(text, d, *options.columns);
      } else if (d.columns > 2) {
        text.fail(line.number, "--columns",
                  fmt::format("{} columns; a plain file holds one (acceleration) or two (time, acceleration) unless "
                              "--columns TIME,ACCEL chooses them (numbers from 1, or header names){}",
                              d.columns,
                              d.header ? fmt::format("; the header (line {}) names {}", d.header->line,
                                                     header_names(*d.header))
                                       : std::string()));
      } else if (d.columns == 2) {
        d.time_index = 0;
        d.accel_index = 1;
      }
    } else if (fields.size() != d.columns) {
      text.fail(line.number, "",
                fmt::format("{} column{} where line {} has {}", fields.size(), fields.size() == 1 ? "" : "s",
                            d.first_data_line, d.columns));
    }
    // Without a column choice every field is a value; with one, only the chosen fields are read.
    if (!chosen) {
      for (std::size_t k = 0; k < fields.size(); ++k) {
        if (fields[k].empty()) {
          text.fail(line.number, "", fmt::format("empty field {} (two separators in a row)", k + 1));
        }
      }
    }
    const auto value = [&](std::size_t k, const std::string& field) {
      if (fields[k].empty()) text.fail(line.number, field, fmt::format("empty field in column {}", k + 1));
      return parse_number(text, fields[k], line.number, field);
    };
    if (d.time_index) d.times.push(value(*d.time_index, d.time_field), line.number);
    d.accels.push(value(d.accel_index, d.accel_field), line.number);
  }
  if (d.accels.size() == 0) {
    text.fail(d.header ? d.header->line : text.last_line_number(), "",
              "no data: the file holds no numeric lines (only comments or a header)");
  }
  return d;
}

/// Column meaning and units, as the header states them (none without a header).
struct PlainUnits {
  std::string time_unit;
  std::string accel_unit;
  std::size_t unit_line = 0;
};

/// The unit a chosen column's header name states: one in brackets ("Table Acc (g)", "acc [m/s2]") always, a suffix
/// after an underscore ("accel_g", "a_cm_s2") only when it is an acceleration unit (so that "table_acc" states none).
std::string stated_accel_unit(const Column& c, double g_m_s2) {
  if (c.unit.empty() || c.unit_in_brackets) return c.unit;
  try {
    (void)acceleration_unit_factor(c.unit, "unit", g_m_s2);
    return c.unit;
  } catch (const InputError&) {
    return {};
  }
}

PlainUnits plain_units(const Text& text, PlainData& d, const ReadOptions& options) {
  PlainUnits u;
  if (!d.header) return u;
  const Header& header = *d.header;
  u.unit_line = header.line;
  if (options.columns) {
    // The user chose the columns: their names need not say what they hold, only their units are read.
    if (d.time_index) u.time_unit = header.columns[*d.time_index].unit;
    u.accel_unit = stated_accel_unit(header.columns[d.accel_index], options.g_m_s2);
    return u;
  }
  if (header.columns.size() != d.columns) {
    text.fail(header.line, "header",
              fmt::format("the header names {} column{} but the data has {}", header.columns.size(),
                          header.columns.size() == 1 ? "" : "s", d.columns));
  }
  const Column& accel_column = header.columns.back();
  if (d.columns == 2 && !is_time_column(header.columns[0])) {
    text.fail(header.line, header.columns[0].name,
              "the first of two columns must be the time (e.g. 'time_s,accel_g'), or choose the columns with "
              "--columns");
  }
  if (!is_accel_column(accel_column) && !header.from_comment) {
    text.fail(header.line, accel_column.name,
              "the acceleration column must be named accel/acc/acceleration with its unit (e.g. 'accel_g'), or "
              "chosen with --columns");
  }
  if (d.columns == 2) u.time_unit = header.columns[0].unit;
  u.accel_unit = accel_column.unit;
  d.accel_field = accel_column.name;
  return u;
}

/// The factor to m/s^2: the header's unit (--units may only confirm it), or --units.
double plain_accel_factor(const Text& text, const PlainData& d, const PlainUnits& u, const ReadOptions& options,
                          RecordMetadata& meta) {
  double factor = 0.0;
  if (!u.accel_unit.empty()) {
    // The header states the unit: --units may only confirm it.
    factor = file_unit_factor(text, u.accel_unit, u.unit_line, d.accel_field, options);
    meta.units_as_read = u.accel_unit;
  } else if (!options.units.empty()) {
    try {
      factor = acceleration_unit_factor(options.units, "--units", options.g_m_s2);
    } catch (const InputError& e) {
      text.fail_file("--units", e.problem());
    }
    meta.units_as_read = options.units;
  } else if (d.header) {
    text.fail(d.header->line, d.accel_field,
              "the header names no acceleration unit; name it (e.g. 'accel_g', 'accel_m_s2', 'accel_cm_s2', "
              "'Acc (g)') or give --units (g, m/s2, cm/s2, gal)");
  } else {
    text.fail_file("--units",
                   "a plain file without a header naming its unit needs --units (g, m/s2, cm/s2, gal)");
  }
  return factor;
}

/// The time column in seconds, checked against the limits of a ground motion (GroundMotionLimits).
std::vector<double> plain_times_s(const Text& text, const PlainData& d, const PlainUnits& u, bool options_chose) {
  double time_factor = 1.0;
  if (u.time_unit == "ms") {
    time_factor = 1e-3;
  } else if (!u.time_unit.empty() && u.time_unit != "s" && u.time_unit != "sec") {
    text.fail(d.header->line, options_chose ? d.time_field : d.header->columns[0].name,
              fmt::format("unknown time unit {} (known: s, ms)", detail::quoted(u.time_unit)));
  }
  using Limits = GroundMotionLimits;
  const Samples& times = d.times;
  const std::string& field = d.time_field;
  std::vector<double> t = times.values;
  if (t.size() > Limits::max_samples) {
    text.fail(times.lines.back(), field,
              fmt::format("{} rows, more than the limit of {} samples of a ground motion", t.size(),
                          Limits::max_samples));
  }
  for (std::size_t i = 0; i < t.size(); ++i) {
    t[i] *= time_factor;
    if (i > 0 && !(t[i] > t[i - 1])) {
      text.fail(times.lines[i], field,
                fmt::format("time {} {} the time {} of line {}; times must increase", times.values[i],
                            t[i] == t[i - 1] ? "repeats" : "is before", times.values[i - 1], times.lines[i - 1]));
    }
    if (i > 0 && t[i] - t[i - 1] < Limits::min_dt_s) {
      text.fail(times.lines[i], field,
                fmt::format("time {} is {:.6g} s after the time {} of line {}, closer than the limit of {:.6g} s "
                            "between samples",
                            times.values[i], t[i] - t[i - 1], times.values[i - 1], times.lines[i - 1],
                            Limits::min_dt_s));
    }
  }
  if (t.size() < 2) {
    text.fail(times.lines.front(), field, "a time/acceleration file needs at least two rows");
  }
  if (!(std::abs(t.front()) <= Limits::max_abs_start_time_s)) {
    text.fail(times.lines.front(), field,
              fmt::format("the record starts at {:.6g} s, beyond the limit of +-{:.6g} s (1 day); shift its times",
                          t.front(), Limits::max_abs_start_time_s));
  }
  const double span = t.back() - t.front();
  if (!(span <= Limits::max_duration_s)) {
    text.fail(times.lines.back(), field,
              fmt::format("the record lasts {:.6g} s (from {:.6g} s to {:.6g} s), more than the limit of {:.6g} s "
                          "(6 h) of a ground motion",
                          span, t.front(), t.back(), Limits::max_duration_s));
  }
  return t;
}

}  // namespace

GroundMotion read_plain(const Text& text, const ReadOptions& options) {
  PlainData d = scan_plain(text, options);
  const PlainUnits units = plain_units(text, d, options);
  RecordMetadata meta;
  if (d.first_comment) metadata_from_title(d.first_comment->text, meta);
  const double factor = plain_accel_factor(text, d, units, options, meta);
  std::vector<double> accel = to_m_s2(text, d.accels, factor, d.accel_field);

  if (!d.time_index) {
    if (!options.dt_s) {
      text.fail_file("--dt", options.columns ? "no time column is chosen; give the time step with --dt"
                                             : "a one-column file holds no times; give its time step with --dt");
    }
    if (!(*options.dt_s > 0.0) || !std::isfinite(*options.dt_s)) {
      text.fail_file("--dt", fmt::format("the time step must be positive and finite, got {}", *options.dt_s));
    }
    return uniform_record(text, std::move(accel), *options.dt_s, std::nullopt, "--dt", std::move(meta), options);
  }

  if (options.dt_s) {
    text.fail_file("--dt", "this file has a time column; --dt applies only to files without one");
  }
  std::vector<double> t = plain_times_s(text, d, units, options.columns.has_value());
  // Uniform when every interval equals the mean interval to 1e-9 relative: times printed with a few decimals
  // ("40.13", "40.14") differ from a uniform grid only by the rounding of their decimal representation.
  const double span = t.back() - t.front();
  const double dt = span / static_cast<double>(t.size() - 1);
  bool uniform = dt > 0.0;
  for (std::size_t i = 1; i < t.size() && uniform; ++i) {
    if (std::abs((t[i] - t[i - 1]) - dt) > 1e-9 * dt) uniform = false;
  }
  if (uniform) return GroundMotion::uniform(std::move(accel), dt, t.front(), std::move(meta));
  return GroundMotion::irregular(std::move(t), std::move(accel), std::move(meta));
}

}  // namespace detail
}  // namespace topple::io
