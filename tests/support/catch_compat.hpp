// Catch2 v2 (Debian's catch2, single header) and v3 (split headers) behind one include.
#pragma once

// The v2 single header wins when both are visible: it needs no compiled library.
#if __has_include(<catch2/catch.hpp>)
#include <catch2/catch.hpp>
#else
#include <catch2/catch_all.hpp>
using Catch::Approx;
#endif
