#pragma once
// Test fixtures: a CSV table as a sweep writes it (header, rows, quoted cells), and the comparison of one of its
// cells with the JSON value of a single run.
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace topple::test {

/// A CSV file as rows of cells (quoted cells unquoted), header first.
[[nodiscard]] std::vector<std::vector<std::string>> read_csv(const std::filesystem::path& p);

/// A CSV table: its header and rows, a cell by row and column name.
struct Table {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  [[nodiscard]] const std::string& at(std::size_t row, const std::string& col) const;
};

[[nodiscard]] Table read_table(const std::filesystem::path& p);

/// Writes `toml` to dir/s.toml, runs `topple sweep` on it with `options`, expects exit status 0 (a test failure naming
/// stderr otherwise) and returns the table it wrote, dir/s.csv.
[[nodiscard]] Table run_sweep(const std::filesystem::path& dir, const std::string& toml,
                              const std::string& options = "--quiet --threads 2");

/// A CSV cell and a JSON value carry the same number (or both are none), compared exactly as doubles (gtest
/// assertions).
void expect_same(const std::string& cell, const nlohmann::json& j, const std::string& key);

}  // namespace topple::test
