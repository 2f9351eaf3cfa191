// What the store's files hold: values, rows and tables as CSV and JSON lines, in the shortest text that reads back
// to the same number (ensemble.hpp, "Determinism" and "Rows").
#include <cmath>
#include <iterator>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <variant>

#include <fmt/compile.h>
#include <fmt/format.h>

#include "ensemble/ensemble_detail.hpp"
#include "topple/ensemble/ensemble.hpp"

namespace topple::ensemble {
namespace {

/// Shortest round-trip text of a number (fmt "{}", Dragonbox for doubles), appended without a format-string parse.
template <class T>
void append_number(std::string& out, T v) {
  char buf[40];
  char* end = fmt::format_to(buf, FMT_COMPILE("{}"), v);
  out.append(buf, end);
}

bool csv_needs_quotes(std::string_view s) {
  if (s.empty()) return false;
  if (s.front() == ' ' || s.back() == ' ') return true;
  return s.find_first_of(",\"\r\n") != std::string_view::npos;
}


}  // namespace

namespace detail {

void append_json_string(std::string& out, std::string_view s) {
  out += '"';
  for (const char ch : s) {
    const auto c = static_cast<unsigned char>(ch);
    switch (ch) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\r': out += "\\r"; break;
      case '\t': out += "\\t"; break;
      default:
        if (c < 0x20) {
          fmt::format_to(std::back_inserter(out), "\\u{:04x}", static_cast<unsigned>(c));
        } else {
          out += ch;
        }
    }
  }
  out += '"';
}


}  // namespace detail

void append_csv_value(std::string& out, const Value& value) {
  std::visit(
      [&out](const auto& v) {
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, std::monostate>) {
          // empty cell
        } else if constexpr (std::is_same_v<T, bool>) {
          out += v ? "true" : "false";
        } else if constexpr (std::is_same_v<T, std::int64_t>) {
          append_number(out, v);
        } else if constexpr (std::is_same_v<T, double>) {
          if (std::isfinite(v)) append_number(out, v);
        } else {
          if (!csv_needs_quotes(v)) {
            out += v;
          } else {
            out += '"';
            for (const char c : v) {
              if (c == '"') out += '"';
              out += c;
            }
            out += '"';
          }
        }
      },
      value);
}

void append_json_value(std::string& out, const Value& value) {
  std::visit(
      [&out](const auto& v) {
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, std::monostate>) {
          out += "null";
        } else if constexpr (std::is_same_v<T, bool>) {
          out += v ? "true" : "false";
        } else if constexpr (std::is_same_v<T, std::int64_t>) {
          append_number(out, v);
        } else if constexpr (std::is_same_v<T, double>) {
          if (std::isfinite(v)) {
            append_number(out, v);
          } else {
            out += "null";
          }
        } else {
          detail::append_json_string(out, v);
        }
      },
      value);
}

std::string csv_header(const Plan& plan) {
  std::string out;
  bool first = true;
  for (const auto& c : plan.columns()) {
    if (!first) out += ',';
    first = false;
    append_csv_value(out, Value{c});
  }
  out += '\n';
  return out;
}

namespace detail {

Layout::Layout(const Plan& plan) : result_count(plan.result_columns.size()) {
  const auto csv_part = [](const std::vector<Value>& values) {
    std::string s;
    for (const auto& v : values) {
      s += ',';
      append_csv_value(s, v);
    }
    return s;
  };
  const auto json_part = [](const std::vector<std::string>& names, const std::vector<Value>& values) {
    std::string s;
    for (std::size_t i = 0; i < values.size(); ++i) {
      s += ',';
      append_json_string(s, names[i]);
      s += ':';
      append_json_value(s, values[i]);
    }
    return s;
  };
  for (const auto& m : plan.motions) {
    motion_csv.push_back(csv_part(m.values));
    motion_json.push_back(json_part(plan.motion_columns, m.values));
  }
  for (const auto& o : plan.objects) {
    object_csv.push_back(csv_part(o.values));
    object_json.push_back(json_part(plan.object_columns, o.values));
  }
  for (const auto& name : plan.result_columns) {
    std::string k = ",";
    append_json_string(k, name);
    k += ':';
    result_json_keys.push_back(std::move(k));
  }
}

namespace {

void check_result_text(const Value& v, std::size_t run) {
  if (has_line_break(v)) {
    throw std::logic_error(fmt::format("ensemble: run {} produced a text value with a line break", run));
  }
}

}  // namespace

/// CSV and JSON-lines text of the runs [begin, end), whose results are `results` (row-major).
void format_rows(const Plan& plan, const Layout& layout, std::size_t begin, std::size_t end,
                 const std::vector<Value>& results, std::string* csv, std::string* jsonl) {
  const std::size_t n_obj = plan.objects.size();
  const std::size_t nres = layout.result_count;
  for (std::size_t run = begin; run < end; ++run) {
    const std::size_t m = run / n_obj;
    const std::size_t o = run % n_obj;
    const Value* r = results.data() + (run - begin) * nres;
    for (std::size_t k = 0; k < nres; ++k) check_result_text(r[k], run);
    if (csv != nullptr) {
      append_number(*csv, run);
      *csv += layout.motion_csv[m];
      *csv += layout.object_csv[o];
      for (std::size_t k = 0; k < nres; ++k) {
        *csv += ',';
        append_csv_value(*csv, r[k]);
      }
      *csv += '\n';
      if (run == begin) csv->reserve(csv->size() * (end - begin) * 9 / 8 + 64);  // rows are about as long as the first
    }
    if (jsonl != nullptr) {
      *jsonl += "{\"run\":";
      append_number(*jsonl, run);
      *jsonl += layout.motion_json[m];
      *jsonl += layout.object_json[o];
      for (std::size_t k = 0; k < nres; ++k) {
        *jsonl += layout.result_json_keys[k];
        append_json_value(*jsonl, r[k]);
      }
      *jsonl += "}\n";
      if (run == begin) jsonl->reserve(jsonl->size() * (end - begin) * 9 / 8 + 64);
    }
  }
}


}  // namespace detail

std::string to_csv(const ResultTable& table) {
  std::string out;
  bool first = true;
  for (const auto& c : table.columns) {
    if (!first) out += ',';
    first = false;
    append_csv_value(out, Value{c});
  }
  out += '\n';
  for (const auto& row : table.rows) {
    for (std::size_t i = 0; i < row.size(); ++i) {
      if (i > 0) out += ',';
      append_csv_value(out, row[i]);
    }
    out += '\n';
  }
  return out;
}

std::string to_jsonl(const ResultTable& table) {
  std::string out;
  for (const auto& row : table.rows) {
    out += '{';
    for (std::size_t i = 0; i < row.size(); ++i) {
      if (i > 0) out += ',';
      detail::append_json_string(out, table.columns[i]);
      out += ':';
      append_json_value(out, row[i]);
    }
    out += "}\n";
  }
  return out;
}

}  // namespace topple::ensemble
