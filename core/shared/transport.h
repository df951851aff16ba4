// The transport of several filtered bounces (Meijer §4.3, nHPSF), written once for C++ and GLSL: a record whose path
// scattered from its filter vertex to a further vertex adds to its own contribution the light the previous frame's
// table holds at that vertex's cell, carried back by the transport weight (the throughput from the filter vertex to
// the scattered one, times the scattered vertex's albedo: D6 keeps albedos out of the table). In double with one
// correctly rounded multiply and one add per channel, then rounded to float once, so every backend makes the same
// bits from the same average.
#ifndef HPSF_CORE_SHARED_TRANSPORT_H
#define HPSF_CORE_SHARED_TRANSPORT_H

#include "prelude.h"

HPSF_SHARED_BEGIN

HPSF_FN vec3 TransportedContribution(vec3 contribution, vec3 weight, dvec3 average) {
  vec3 result;
  for (int c = 0; c < 3; ++c) {
    HPSF_PRECISE double carried = double(weight[c]) * average[c];
    HPSF_PRECISE double total = double(contribution[c]) + carried;
    result[c] = float(total);
  }
  return result;
}

HPSF_SHARED_END

#endif  // HPSF_CORE_SHARED_TRANSPORT_H
