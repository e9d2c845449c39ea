// FACET_TEST_ADDRESS_SANITIZER: defined when this program is built with AddressSanitizer, by GCC
// (which defines __SANITIZE_ADDRESS__) or by clang (which answers __has_feature(address_sanitizer)).
#pragma once

#if defined(__SANITIZE_ADDRESS__)
#define FACET_TEST_ADDRESS_SANITIZER 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define FACET_TEST_ADDRESS_SANITIZER 1
#endif
#endif
