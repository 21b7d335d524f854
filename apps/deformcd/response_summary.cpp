#include "response_summary.h"

#include <iomanip>
#include <sstream>

#include "option_values.h"

namespace deformcd::app {

void ResponseTally::add(int frame, const ResponseCounts& counts) {
  ++frames;
  asleep = counts.asleep;
  // Between bodies: with self-contact each body's own near pairs are constraints in every
  // frame, in contact with another body or not.
  const std::uint64_t constraints = counts.between_bodies;
  if (counts.contact_constraints() > constraints) ++frames_with_own;
  if (constraints > 0) {
    ++frames_with_constraints;
    if (first_active < 0) first_active = frame;
    last_active = frame;
  }
  if (constraints > most_constraints) {
    most_constraints = constraints;
    most_at = frame;
  }
  // Relative to the thickness (a cross-multiplied comparison; thickness 0: no pair yet).
  if (counts.closest_thickness > 0.0f &&
      (closest_thickness == 0.0f ||
       counts.closest_distance * closest_thickness < closest_distance * counts.closest_thickness)) {
    closest_distance = counts.closest_distance;
    closest_thickness = counts.closest_thickness;
    closest_at = frame;
  }
}

std::string describe_response(const ResponseTally& t, std::size_t bodies, bool sleeps) {
  std::ostringstream out;
  if (t.frames_with_constraints == 0) {
    out << "no constraints between bodies in " << count_of(t.frames, "frame", "frames")
        << " (the bodies never came within their contact thickness)";
  } else {
    out << "constraints between bodies in " << t.frames_with_constraints << " of "
        << count_of(t.frames, "frame", "frames") << " (" << t.first_active << "-" << t.last_active
        << "), at most " << t.most_constraints << " at once (frame " << t.most_at << ")";
  }
  if (t.frames_with_own > 0)
    out << "; a body's own (self-contact) in " << count_of(t.frames_with_own, "frame", "frames");
  if (t.closest_thickness > 0.0f) {
    out << "; closest surfaces " << std::setprecision(3) << t.closest_distance << " m apart (frame "
        << t.closest_at << "), " << std::fixed << std::setprecision(2)
        << t.closest_distance / t.closest_thickness << " x the thickness kept ("
        << std::defaultfloat << std::setprecision(3) << t.closest_thickness << " m)";
  }
  if (sleeps)
    out << ", " << t.asleep << " of " << count_of(bodies, "body", "bodies") << " asleep at the end";
  return out.str();
}

}  // namespace deformcd::app
