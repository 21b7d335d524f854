#pragma once
// DEFORMCD_UNDER_ASAN is defined when the test is built with AddressSanitizer (GCC says so with
// __SANITIZE_ADDRESS__, Clang with __has_feature): the long scene runs shorten there (about 20x
// slower).

#if defined(__SANITIZE_ADDRESS__)
#define DEFORMCD_UNDER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define DEFORMCD_UNDER_ASAN 1
#endif
#endif
