// OutputFile: results appear under their final name only complete (io/output_file.hpp).
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "topple/core/error.hpp"
#include "topple/core/output_file.hpp"

namespace fs = std::filesystem;
using topple::io::OutputFile;

namespace {

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("topple_output_file_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string read_all(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::size_t entries(const fs::path& dir) {
  return static_cast<std::size_t>(std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
}

}  // namespace

TEST(OutputFile, CommitRenamesIntoPlaceAndLeavesNoTemporary) {
  const fs::path dir = fresh_dir("commit");
  {
    OutputFile f(dir / "result.csv");
    f.stream() << "a,b\n1,2\n";
    EXPECT_FALSE(fs::exists(dir / "result.csv"));  // nothing under the final name before commit
    EXPECT_TRUE(fs::exists(f.temporary_path()));
    f.commit();
  }
  EXPECT_EQ(read_all(dir / "result.csv"), "a,b\n1,2\n");
  EXPECT_EQ(entries(dir), 1U);
}

TEST(OutputFile, DestroyedWithoutCommitLeavesNothing) {
  const fs::path dir = fresh_dir("abandon");
  {
    OutputFile f(dir / "result.csv");
    f.stream() << "partial";
  }
  EXPECT_EQ(entries(dir), 0U);
}

TEST(OutputFile, ExistingFileIsReplacedOnlyOnCommit) {
  const fs::path dir = fresh_dir("replace");
  topple::io::write_file_atomically(dir / "r.json", "old");
  {
    OutputFile f(dir / "r.json");
    f.stream() << "new";
    EXPECT_EQ(read_all(dir / "r.json"), "old");
  }
  EXPECT_EQ(read_all(dir / "r.json"), "old");  // abandoned: the old file stands
  topple::io::write_file_atomically(dir / "r.json", "new");
  EXPECT_EQ(read_all(dir / "r.json"), "new");
}

TEST(OutputFile, UnwritableDirectoryThrowsOutputErrorNamingThePath) {
  const fs::path dir = fresh_dir("missing") / "no" / "such";
  try {
    OutputFile f(dir / "x.csv");
    FAIL() << "expected OutputError";
  } catch (const topple::OutputError& e) {
    EXPECT_NE(std::string(e.what()).find("x.csv"), std::string::npos) << e.what();
  }
}

TEST(OutputFile, ADirectoryAsTheFinalNameIsRefusedAtOnceLeavingNothing) {
  // `slide ... --out /tmp` used to run the whole analysis, make its temporary beside the directory (in '/') and only
  // then fail on the rename: the target is checked when the output is opened, before any work.
  const fs::path dir = fresh_dir("is_dir");
  fs::create_directories(dir / "out");
  for (const fs::path& target : {dir / "out", fs::path((dir / "out").string() + "/")}) {
    try {
      OutputFile f(target);
      FAIL() << "expected OutputError for " << target;
    } catch (const topple::OutputError& e) {
      EXPECT_NE(std::string(e.what()).find("is a directory"), std::string::npos) << e.what();
    }
  }
  EXPECT_EQ(entries(dir), 1U);  // only out/, no temporary beside it
  EXPECT_EQ(entries(dir / "out"), 0U);
}
