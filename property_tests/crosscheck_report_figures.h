// Lookups into a cross-check report (verifier/contract/crosscheck.h) that the property tests read: a level's verdict
// and a backend's quality figures.
#ifndef HPSF_PROPERTY_TESTS_CROSSCHECK_REPORT_FIGURES_H
#define HPSF_PROPERTY_TESTS_CROSSCHECK_REPORT_FIGURES_H

#include <stdexcept>
#include <string>

#include "verifier/contract/crosscheck.h"

namespace hpsf::testing {

// Level 1..4 of the contract.
inline const LevelVerdict& Level(const CrosscheckReport& report, int level) {
  return report.levels[std::size_t(level - 1)];
}

inline const QualityFigures& QualityOf(const CrosscheckReport& report, const std::string& backend) {
  for (const QualityFigures& q : report.quality) {
    if (q.backend == backend) return q;
  }
  throw std::runtime_error("no quality figures for " + backend);
}

}  // namespace hpsf::testing

#endif  // HPSF_PROPERTY_TESTS_CROSSCHECK_REPORT_FIGURES_H
