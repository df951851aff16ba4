#include "core/filter_config.h"

#include <functional>
#include <string>

#include <gtest/gtest.h>

#include "core/error.h"

namespace hpsf {
namespace {

void ExpectRejected(const std::function<void(FilterConfig&)>& change, const std::string& option) {
  FilterConfig config;
  change(config);
  try {
    config.Validate();
    ADD_FAILURE() << "accepted " << config.ToString();
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(option + ": ", 0), 0u) << e.what();
  }
}

TEST(FilterConfig, DefaultsAreValid) { EXPECT_NO_THROW(FilterConfig{}.Validate()); }

TEST(FilterConfig, EachBadValueNamesItsOption) {
  ExpectRejected([](FilterConfig& c) { c.filter_width_px = 0.0f; }, "--filter-width");
  ExpectRejected([](FilterConfig& c) { c.filter_width_px = std::numeric_limits<float>::infinity(); }, "--filter-width");
  ExpectRejected([](FilterConfig& c) { c.jitter_scale = -1.0f; }, "--jitter");
  ExpectRejected([](FilterConfig& c) { c.jitter_scale = std::numeric_limits<float>::quiet_NaN(); }, "--jitter");
  ExpectRejected([](FilterConfig& c) { c.cell_size = 0.0f; }, "--cell-size");
  ExpectRejected([](FilterConfig& c) { c.cell_size = 1e-40f; }, "--cell-size");
  ExpectRejected([](FilterConfig& c) { c.cell_size = 1e38f * 10.0f; }, "--cell-size");
  ExpectRejected([](FilterConfig& c) { c.level_min = -127; }, "--level-min");
  ExpectRejected([](FilterConfig& c) { c.level_max = 127; }, "--level-max");
  ExpectRejected([](FilterConfig& c) { c.level_min = 5, c.level_max = 4; }, "--level-min");
  ExpectRejected([](FilterConfig& c) { c.capacity = 1000; }, "--capacity");
  ExpectRejected([](FilterConfig& c) { c.capacity = 0; }, "--capacity");
  ExpectRejected([](FilterConfig& c) { c.probe_limit = 0; }, "--probe-limit");
  ExpectRejected([](FilterConfig& c) { c.capacity = 8, c.probe_limit = 9; }, "--probe-limit");
  ExpectRejected([](FilterConfig& c) { c.fingerprint_bits = 7; }, "--fingerprint-bits");
  ExpectRejected([](FilterConfig& c) { c.fingerprint_bits = 33; }, "--fingerprint-bits");
  ExpectRejected([](FilterConfig& c) { c.normal = {NormalMode::kOctahedral, 17}; }, "--normal");
}

TEST(FilterConfig, ParsesNormalKeysAndAccumulation) {
  EXPECT_EQ(ParseNormalKey("none").mode, NormalMode::kNone);
  EXPECT_EQ(ParseNormalKey("sign").mode, NormalMode::kSign);
  EXPECT_EQ(ParseNormalKey("octahedral:7").octahedral_bits, 7u);
  EXPECT_EQ(ParseNormalKey("octahedral:16").ToString(), "octahedral:16");
  for (const char* bad : {"octahedral:", "octahedral:0", "octahedral:17", "octahedral:3x", "signs", ""}) {
    EXPECT_THROW(ParseNormalKey(bad), ConfigError) << bad;
  }
  EXPECT_EQ(ParseAccumulation("float32"), Accumulation::kFloat32);
  EXPECT_THROW(ParseAccumulation("double"), ConfigError);
}

TEST(FilterConfig, KeyParamsCarryTheHostComputedValues) {
  FilterConfig config;
  config.lod = false;
  config.cell_size = 3.0f;
  config.capacity = 1u << 10;
  const shared::KeyParams p = MakeKeyParams(config, 0.5f, 42);
  EXPECT_EQ(p.inverse_cell_size, 1.0f / 3.0f);
  EXPECT_EQ(p.capacity_mask, 1023u);
  EXPECT_EQ(p.lod_enabled, 0u);
  EXPECT_EQ(p.record_count, 42u);
  EXPECT_THROW(MakeKeyParams(config, std::numeric_limits<float>::infinity(), 1), ConfigError);
}

}  // namespace
}  // namespace hpsf
