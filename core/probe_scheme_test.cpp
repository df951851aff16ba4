// The probing schemes of core/shared/probe_scheme.h against orders written out by hand from their definitions:
// every backend and the checker walk candidates through these functions, so a mistake here would be shared by
// all of them and invisible to the contract. Exhaustive over small tables.

#include "core/shared/probe_scheme.h"

#include <cstdint>
#include <set>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/probing.h"

namespace hpsf {
namespace {

// The candidates of slot0, in order, straight from the definitions in the header's comment.
std::vector<std::uint32_t> OrderByDefinition(ProbeKind kind, std::uint32_t capacity, std::uint32_t size,
                                             std::uint32_t slot0) {
  std::vector<std::uint32_t> order;
  std::uint32_t first = slot0;
  if (kind == ProbeKind::kBucket) first = slot0 / size * size;
  if (kind == ProbeKind::kBucketWindow) first = slot0 < capacity - size ? slot0 : capacity - size;
  for (std::uint32_t k = 0; k < size; ++k)
    order.push_back(kind == ProbeKind::kLinear ? (slot0 + k) % capacity : first + k);
  return order;
}

struct Shape {
  ProbeKind kind;
  std::uint32_t capacity;
  std::uint32_t size;
};

std::vector<Shape> SmallShapes() {
  std::vector<Shape> shapes;
  for (std::uint32_t capacity = 1; capacity <= 32; capacity *= 2) {
    for (std::uint32_t size = 1; size <= capacity; ++size) {
      shapes.push_back({ProbeKind::kLinear, capacity, size});
      shapes.push_back({ProbeKind::kBucketWindow, capacity, size});
      if ((size & (size - 1)) == 0) shapes.push_back({ProbeKind::kBucket, capacity, size});
    }
  }
  return shapes;
}

std::string Name(const Shape& s) {
  return ToString(s.kind) + ":" + std::to_string(s.size) + " of " + std::to_string(s.capacity);
}

TEST(ProbeScheme, CandidatesAndTheirIndicesFollowTheDefinitions) {
  for (const Shape& shape : SmallShapes()) {
    const shared::ProbeScheme scheme = MakeProbeScheme(shape.kind, shape.capacity, shape.size);
    for (std::uint32_t slot0 = 0; slot0 < shape.capacity; ++slot0) {
      const std::vector<std::uint32_t> order = OrderByDefinition(shape.kind, shape.capacity, shape.size, slot0);
      EXPECT_EQ(shared::FirstCandidate(scheme, slot0), order[0]) << Name(shape) << ", slot0 " << slot0;
      for (std::uint32_t k = 0; k < shape.size; ++k) {
        ASSERT_EQ(shared::CandidateSlot(scheme, slot0, k), order[k]) << Name(shape) << ", slot0 " << slot0;
      }
      for (std::uint32_t slot = 0; slot < shape.capacity + 2; ++slot) {
        std::uint32_t expected = shared::kNoCandidate;
        for (std::uint32_t k = 0; k < shape.size; ++k) {
          if (order[k] == slot) expected = k;
        }
        ASSERT_EQ(shared::ProbeIndex(scheme, slot0, slot), expected)
            << Name(shape) << ", slot0 " << slot0 << ", slot " << slot;
      }
    }
  }
}

// SlotAfter(slot, d) names t exactly when some key's order holds slot and, d steps later, t.
TEST(ProbeScheme, SlotAfterIsWhatSomeOrderHoldsLater) {
  for (const Shape& shape : SmallShapes()) {
    const shared::ProbeScheme scheme = MakeProbeScheme(shape.kind, shape.capacity, shape.size);
    std::set<std::tuple<std::uint32_t, std::uint32_t, std::uint32_t>> later;  // slot, distance, slot after
    for (std::uint32_t slot0 = 0; slot0 < shape.capacity; ++slot0) {
      const std::vector<std::uint32_t> order = OrderByDefinition(shape.kind, shape.capacity, shape.size, slot0);
      for (std::uint32_t a = 0; a < order.size(); ++a) {
        for (std::uint32_t b = a + 1; b < order.size(); ++b) later.insert({order[a], b - a, order[b]});
      }
    }
    for (std::uint32_t slot = 0; slot < shape.capacity; ++slot) {
      for (std::uint32_t distance = 1; distance <= shape.capacity; ++distance) {
        const std::uint32_t after = shared::SlotAfter(scheme, slot, distance);
        if (after == shared::kNoCandidate) {
          for (std::uint32_t t = 0; t < shape.capacity; ++t) {
            EXPECT_EQ(later.count({slot, distance, t}), 0u) << Name(shape) << ", " << slot << " + " << distance;
          }
        } else {
          EXPECT_EQ(later.count({slot, distance, after}), 1u) << Name(shape) << ", " << slot << " + " << distance;
        }
      }
    }
  }
}

TEST(ProbeScheme, ASchemeIsParsedOrNamedAsTheBadOption) {
  EXPECT_EQ(ParseProbing("linear").kind, ProbeKind::kLinear);
  EXPECT_FALSE(ParseProbing("bucket").size.has_value());
  const Probing window = ParseProbing("bucket-window:32");
  EXPECT_EQ(window.kind, ProbeKind::kBucketWindow);
  EXPECT_EQ(window.size, 32u);
  for (const char* bad : {"", "cuckoo", "bucket:", "bucket:0", "bucket:-4", "bucket:4x", "linear:99999999999"}) {
    try {
      ParseProbing(bad);
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find("--probing"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace hpsf
