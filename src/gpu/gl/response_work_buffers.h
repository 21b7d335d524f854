#pragma once
// Binding points and layout of GlContactResponse's private work buffers: the projection's
// compaction of its acting constraints and touched nodes, which no C++ struct reads and which
// the CPU backend keeps in host vectors (src/cpu/cpu_contact_response.h), so they are not in
// gpu::Binding. Mirrored by shaders/response/response_work_buffers.glsl
// (tests/gl/layout_agreement_test.cpp checks). Numbered after gpu::Binding's last, since the
// response's passes bind these beside its public buffers. No GL here.

#include <cstdint>

namespace deformcd::gl {

inline constexpr std::uint32_t kContactActingBinding = 40;   // uint per constraint
inline constexpr std::uint32_t kActingListBinding = 41;      // uint per acting constraint
inline constexpr std::uint32_t kNodeActiveSlotBinding = 42;  // uint per node list entry
inline constexpr std::uint32_t kTouchedNodeBinding = 43;     // uint per touched node
inline constexpr std::uint32_t kResponseStateBinding = 44;   // uint[kResponseStateWords]
// The sweep's order (response::SweepOrder, from the host): acting places colour by colour, and
// each colour's first entry in it (one more than the colours).
inline constexpr std::uint32_t kSweepOrderBinding = 45;    // uint per acting constraint
inline constexpr std::uint32_t kSweepColoursBinding = 46;  // uint per colour + 1

// The state buffer's size in uints, and its words (RESPONSE_*): the counts of a projection's
// acting contacts, acting constraints and touched nodes, the stray and residual flags, and the
// glDispatchComputeIndirect triples of the residual and slide passes.
inline constexpr std::uint32_t kResponseStateWords = 14;
inline constexpr std::uint32_t kActingContactsWord = 0;
inline constexpr std::uint32_t kActingTotalWord = 1;
inline constexpr std::uint32_t kTouchedNodesWord = 2;
inline constexpr std::uint32_t kStrayFlagWord = 3;
inline constexpr std::uint32_t kResidualFlagWord = 4;
inline constexpr std::uint32_t kResidualArgsWord = 8;
inline constexpr std::uint32_t kSlidePassArgsWord = 11;

}  // namespace deformcd::gl
