#pragma once
/// \file limits.h
/// The limits every entry point applies (World, Detector, the deformcd tool, the Python
/// module), with the one check each uses, so that all of them refuse the same values with the
/// same message. docs/reliability.md explains each.

#include <string>

#include "deformcd/error.h"

namespace deformcd {

/// The most CPU threads a World or a Detector runs on (DetectorOptions::threads,
/// WorldOptions::cpu_threads; the tool's --threads and Python's threads=): past a few per core
/// more threads only cost memory (oneTBB reserves a stack per thread), and counts in the
/// millions crashed oneTBB's initialisation. Larger counts are refused, not clamped.
inline constexpr int kMaxThreads = 256;

/// Throws InputError "`name`: must be 0 (every core) or 1 to 256 (deformcd::kMaxThreads), got
/// N" unless `threads` is in 0..kMaxThreads.
inline void check_thread_count(const std::string& name, long long threads) {
  if (threads >= 0 && threads <= kMaxThreads) return;
  throw InputError(name, "must be 0 (every core) or 1 to " + std::to_string(kMaxThreads) +
                             " (deformcd::kMaxThreads), got " + std::to_string(threads));
}

/// The coordinate range in which contacts do not depend on the units. The narrow phase's
/// tolerances are relative to each pair's own lengths, but it computes in float, and products
/// of four lengths overflow past about 4e9 and underflow below about 3e-12: there the same
/// meshes gave other contacts (extra "coplanar" pairs, or none). So a position past
/// +-kMaxCoordinate is refused (InputError naming the mesh and the vertex: Detector positions
/// given as host arrays, and every body's nodes when it is built), and so is a Detector mesh
/// whose extent (its bounding box's largest side) is not zero but below kMinMeshExtent. Within
/// these, a scene scaled by a power of ten gives the same contact pairs
/// (tests/detector/coordinate_range_test.cpp).
inline constexpr float kMaxCoordinate = 1.0e9f;
/// The smallest extent (largest side of the bounding box) of a mesh that is not a single point;
/// see kMaxCoordinate.
inline constexpr float kMinMeshExtent = 1.0e-10f;

}  // namespace deformcd
