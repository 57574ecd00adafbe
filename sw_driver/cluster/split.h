// The sort-middle renderer's split (README.md, step 3 and "The fill
// rule"): a screen triangle to two trapezoids at its middle vertex, each cut
// at the stripe boundaries, each piece handed to the sink with the stripe it
// belongs to. No allocation.
#pragma once

#include "cluster/records.h"

namespace tessera::cluster {

class TrapezoidSink {
 public:
  virtual ~TrapezoidSink() = default;
  virtual void put(unsigned stripe, const Trapezoid& trapezoid) = 0;
};

// Splits `triangle` (any winding; zero area gives nothing) for a screen of
// `screen_height` rows in `p` stripes (stripes.h), dropping rows off the
// screen. Returns the number of pieces put; 0, and nothing counted, when
// stripe_parameters_error(screen_height, p) is not null or a vertex lies
// beyond +-MAX_COORDINATE. `counters`, when given, gains triangles_split,
// trapezoids_nonempty, trapezoids_out and trapezoid_rows_out.
unsigned split_triangle(const ScreenTriangle& triangle, unsigned screen_height, unsigned p, TrapezoidSink& sink,
                        WorkCounters* counters = nullptr);

}  // namespace tessera::cluster
