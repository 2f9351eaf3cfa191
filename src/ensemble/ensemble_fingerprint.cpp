// The fingerprint of an expanded plan (ensemble.hpp, plan_fingerprint): what the store compares to tell whether
// its chunks belong to the plan being run.
#include <bit>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <unordered_map>

#include <fmt/format.h>

#include "ensemble/ensemble_detail.hpp"
#include "topple/ensemble/ensemble.hpp"

namespace topple::ensemble {

namespace {

/// Two FNV-1a-style 64-bit hashes with different offset bases, fed the same data 8 bytes at a time (the samples of
/// long records are hashed on every run: a byte at a time would cost milliseconds).
struct Fingerprint {
  std::uint64_t a = 14695981039346656037ULL;
  std::uint64_t b = 0x9e3779b97f4a7c15ULL;
  static constexpr std::uint64_t kPrime = 1099511628211ULL;

  void word(std::uint64_t w) {
    a = (a ^ w) * kPrime;
    b = (b ^ (w >> 32 | w << 32)) * kPrime;
  }
  void bytes(const void* data, std::size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    std::size_t i = 0;
    for (; i + 8 <= n; i += 8) {
      std::uint64_t w = 0;
      std::memcpy(&w, p + i, 8);
      word(w);
    }
    for (; i < n; ++i) word(p[i]);
  }
  void text(std::string_view s) {
    const std::uint64_t n = s.size();
    bytes(&n, sizeof n);
    bytes(s.data(), s.size());
  }
  void number(double x) {
    const auto bits = std::bit_cast<std::uint64_t>(x);
    bytes(&bits, sizeof bits);
  }
  void count(std::uint64_t n) { bytes(&n, sizeof n); }
  [[nodiscard]] std::string hex() const { return fmt::format("{:016x}{:016x}", a, b); }
};

void hash_motion(Fingerprint& f, const GroundMotion& g) {
  f.count(g.size());
  f.count(g.is_uniform() ? 1 : 0);
  f.number(g.dt_s());
  f.number(g.start_time_s());
  const auto a = g.accel_m_s2();
  f.bytes(a.data(), a.size_bytes());
  if (!g.is_uniform()) {
    for (std::size_t i = 0; i < g.size(); ++i) f.number(g.time_s(i));
  }
}

}  // namespace

std::string motion_fingerprint(const GroundMotion& motion) {
  Fingerprint f;
  hash_motion(f, motion);
  return f.hex();
}

std::string plan_fingerprint(const Plan& plan) {
  Fingerprint f;
  f.text("topple-ensemble/1");
  for (const auto& c : plan.columns()) f.text(c);
  f.count(plan.chunk_size());
  f.count(plan.motions.size());
  f.count(plan.objects.size());
  f.text(plan.identity);
  std::unordered_map<const GroundMotion*, std::string> base_hashes;
  const detail::Layout layout(plan);
  for (std::size_t m = 0; m < plan.motions.size(); ++m) {
    const auto& mc = plan.motions[m];
    auto it = base_hashes.find(mc.base.get());
    if (it == base_hashes.end()) {
      Fingerprint fb;
      hash_motion(fb, *mc.base);
      it = base_hashes.emplace(mc.base.get(), fb.hex()).first;
    }
    f.text(it->second);
    f.number(mc.transform.time_scale);
    f.number(mc.transform.target_pga_m_s2.value_or(-1.0));
    f.number(mc.transform.factor.value_or(0.0));
    f.count(mc.transform.factor ? 1 : 0);
    f.count(mc.transform.invert ? 1 : 0);
    f.text(layout.motion_csv[m]);
  }
  for (const auto& s : layout.object_csv) f.text(s);
  return f.hex();
}

}  // namespace topple::ensemble
