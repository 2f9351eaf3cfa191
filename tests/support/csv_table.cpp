// CSV tables of sweeps for the tests (csv_table.hpp).
#include "support/csv_table.hpp"

#include <algorithm>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

#include <gtest/gtest.h>

#include "support/shared_data.hpp"

namespace topple::test {

std::vector<std::vector<std::string>> read_csv(const std::filesystem::path& p) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream in(slurp(p));
  std::string line;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::string cell;
    bool quoted = false;
    for (std::size_t i = 0; i < line.size(); ++i) {
      const char c = line[i];
      if (quoted) {
        if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
          cell += '"';
          ++i;
        } else if (c == '"') {
          quoted = false;
        } else {
          cell += c;
        }
      } else if (c == '"') {
        quoted = true;
      } else if (c == ',') {
        cells.push_back(cell);
        cell.clear();
      } else {
        cell += c;
      }
    }
    cells.push_back(cell);
    rows.push_back(std::move(cells));
  }
  return rows;
}

const std::string& Table::at(std::size_t row, const std::string& col) const {
  const auto it = std::find(header.begin(), header.end(), col);
  if (it == header.end()) throw std::runtime_error("no column " + col);
  return rows.at(row).at(static_cast<std::size_t>(it - header.begin()));
}

Table read_table(const std::filesystem::path& p) {
  auto all = read_csv(p);
  Table t;
  t.header = all.at(0);
  t.rows.assign(all.begin() + 1, all.end());
  return t;
}

Table run_sweep(const std::filesystem::path& dir, const std::string& toml, const std::string& options) {
  write_file(dir / "s.toml", toml);
  const CommandResult r = run_cli("sweep '" + (dir / "s.toml").string() + "' " + options);
  if (r.exit_code != 0) {
    ADD_FAILURE() << "sweep exited " << r.exit_code << "\n" << toml << r.err;
    return {};
  }
  return read_table(dir / "s.csv");
}

void expect_same(const std::string& cell, const nlohmann::json& j, const std::string& key) {
  SCOPED_TRACE(key + ": csv '" + cell + "', json " + j.dump());
  if (j.is_null()) {
    EXPECT_EQ(cell, "");
  } else if (j.is_boolean()) {
    EXPECT_EQ(cell, j.get<bool>() ? "true" : "false");
  } else if (j.is_string()) {
    EXPECT_EQ(cell, j.get<std::string>());
  } else {
    ASSERT_FALSE(cell.empty());
    EXPECT_EQ(std::strtod(cell.c_str(), nullptr), j.get<double>());
  }
}

}  // namespace topple::test
