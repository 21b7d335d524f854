#pragma once
// The bvh broad phase's refit alone (cpu::BvhTrees::refit: every tree's boxes and area ratio),
// on the contact frames of a peer comparison, for the thread scaling of the one part of a bvh
// pass that is neither the traversal nor the triangle test.

#include <benchmark/benchmark.h>

#include "contact_frames.h"

namespace deformcd::bench {

/// One iteration refits the trees to every frame once (positions read in place, written
/// untimed); `threads` 0 is every core.
void refit_row(benchmark::State& state, const ContactFrames& frames, int threads);

}  // namespace deformcd::bench
