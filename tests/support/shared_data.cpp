#include "support/shared_data.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>

extern char** environ;

#include <array>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <random>
#include <sstream>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <stdexcept>

namespace topple::test {

std::filesystem::path shared_dir() {
  if (const char* env = std::getenv("TOPPLE_SHARED_DIR")) return env;
  return TOPPLE_SHARED_DIR;
}

std::filesystem::path shared_record(const std::string& name) { return shared_dir() / "records" / name; }

bool have_shared() { return std::filesystem::exists(shared_dir() / "records"); }

namespace {
}  // namespace

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

nlohmann::json run_json(const std::string& args) {
  const auto r = run_cli(args);
  EXPECT_EQ(r.exit_code, 0) << args << "\n" << r.err;
  return nlohmann::json::parse(r.out);
}

CommandResult run_cli(const std::string& args, int timeout_s) {
  TempDir tmp;
  const auto out = tmp.path() / "out.txt";
  const auto err = tmp.path() / "err.txt";
  const std::string limit = timeout_s > 0 ? "timeout -s KILL " + std::to_string(timeout_s) + " " : "";
  const std::string cmd = limit + "'" + TOPPLE_CLI_PATH + "' " + args + " >'" + out.string() + "' 2>'" +
                          err.string() + "' </dev/null";
  const int status = std::system(cmd.c_str());
  CommandResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = slurp(out);
  r.err = slurp(err);
  return r;
}

CommandResult run_example(const std::string& script, const std::string& args) {
  TempDir tmp;
  const auto out = tmp.path() / "out.txt";
  const std::string cmd = std::string("TOPPLE='") + TOPPLE_CLI_PATH + "' '" + TOPPLE_SOURCE_DIR + "/examples/" + script +
                          "' " + args + " >'" + out.string() + "' 2>&1 </dev/null";
  const int status = std::system(cmd.c_str());
  CommandResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = slurp(out);
  return r;
}

TempDir::TempDir() {
  std::random_device rd;
  const auto base = std::filesystem::temp_directory_path();
  for (int attempt = 0; attempt < 100; ++attempt) {
    auto candidate = base / ("topple-test-" + std::to_string(rd()));
    if (std::filesystem::create_directory(candidate)) {
      path_ = candidate;
      return;
    }
  }
  throw std::runtime_error("cannot create a temporary directory");
}

TempDir::~TempDir() {
  std::error_code ec;
  std::filesystem::remove_all(path_, ec);
}

void write_file(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

void write_zero_record(const std::filesystem::path& path, int samples, double dt_s) {
  std::ostringstream text;
  text << "# Time Series: zero\n# Time (s),Acceleration (g's)\n";
  char line[64];
  for (int i = 0; i < samples; ++i) {
    std::snprintf(line, sizeof line, "%.6f,0\n", dt_s * i);
    text << line;
  }
  write_file(path, text.str());
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto pos = text.find(what); pos != std::string::npos; pos = text.find(what, pos + 1)) ++n;
  return n;
}

pid_t spawn_cli(const std::vector<std::string>& args, const std::filesystem::path& err) {
  std::vector<std::string> argv_s{TOPPLE_CLI_PATH};
  argv_s.insert(argv_s.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : argv_s) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = -1;
  const int rc = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  return rc == 0 ? pid : -1;
}

SyntheticStation::SyntheticStation(const std::filesystem::path& dir) {
  const auto quote = [](const std::filesystem::path& p) { return fmt::format("'{}'", p.string()); };
  (void)run_json("synth --components 3 --pga 0.3g --freq 2.5Hz --duration 20 --seed 4 --azimuths 0,90 --json --out " +
                 quote(dir / "m.csv"));
  h1 = quote(dir / "m.h1.csv");
  h2 = quote(dir / "m.h2.csv");
  v = quote(dir / "m.v.csv");
}

CollinearPair kocaeli_with_zero_partner(const std::filesystem::path& dir) {
  write_zero_record(dir / "zero.csv", 26780, 0.005);  // on the record's grid: 26780 samples at 0.005 s
  return {fmt::format("'{}'", shared_record("slammer/Kocaeli_1999_ATS-090.csv").string()),
          fmt::format("'{}'", (dir / "zero.csv").string())};
}

}  // namespace topple::test
