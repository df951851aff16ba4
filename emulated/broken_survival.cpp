#include "emulated/broken_survival.h"

namespace hpsf {

std::vector<float> SurvivalDraws(const RecordBatch& batch, std::uint32_t seed) {
  std::vector<float> draws(batch.records.size(), 0.0f);
  for (std::size_t i = 0; i < draws.size(); ++i) {
    const Record& r = batch.records[i];
    if (shared::RecordHasVertex(r)) {
      draws[i] =
          SurvivalDraw(seed, batch.frame, shared::RecordPixel(r), shared::RecordSample(r), shared::RecordBounce(r));
    }
  }
  return draws;
}

RecordBatch DecidedBeforeTheFrame(const RecordBatch& traced, const PreviousTableView& view, std::uint32_t seed) {
  RecordBatch decided = traced;
  const std::vector<float> draws = SurvivalDraws(traced, seed);
  for (std::size_t i = 0; i < decided.records.size(); ++i) {
    Record& r = decided.records[i];
    if (!shared::RecordHasVertex(r)) continue;
    const glm::vec3 light(r.contribution);
    r.contribution = glm::vec4(SurvivingContribution(view.survival(), light, draws[i], view.Probability(r)), 0.0f);
  }
  return decided;
}

}  // namespace hpsf
