// SPDX-License-Identifier: MIT
// minor_loop_area.cpp: Fig. 15's minor-loop area (Example 4: LuGre, σ0 = 6,
// bimodal input 0, 0.5, 1, 1.5) from C++17, through CMake's
// find_package(hystviz) (tests/libhystviz/cmake/CMakeLists.txt):
//
//     find_package(hystviz 0.1 REQUIRED)
//     target_link_libraries(area PRIVATE hystviz::hystviz)
//
// The core's structs are the caller's; each *_free is tied to a scope here.
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>

#include <hystviz.h>

static_assert(HYSTVIZ_VERSION_CHECK(0, 1, 0), "libhystviz 0.1.0 or later is needed");

namespace {

// Throws the library's message when a call fails.
void check(int status, const hy_error &err)
{
    if (status != HY_OK)
        throw std::runtime_error(err.msg);
}

template <class T, void (*Free)(T *)> struct freer {
    void operator()(T *p) const { Free(p); }
};
template <class T, void (*Free)(T *)> using scoped = std::unique_ptr<T, freer<T, Free>>;

} // namespace

int main()
{
    try {
        // the library this program runs with has the major version of the headers it was built with
        if (std::stoi(hy_version()) != HYSTVIZ_VERSION_MAJOR)
            throw std::runtime_error(std::string("libhystviz ") + hy_version() + " is not " + HYSTVIZ_VERSION_STRING);
        hy_error err{};
        hy_model m{};
        hy_model_lugre_init(&m, 6, 1, 1, 2, 1, 1);
        hy_input in{};
        check(hy_input_bimodal(&in, 0, 0.5, 1, 1.5, nullptr, HY_SHAPE_LINEAR, &err), err);
        scoped<hy_input, hy_input_free> in_owner(&in);
        hy_steady st{};
        check(hy_steady_init(&st, &m, &in, &err), err);
        scoped<hy_steady, hy_steady_free> st_owner(&st);
        hy_loops loops{};
        check(hy_loops_find(&st, &loops, &err), err);
        scoped<hy_loops, hy_loops_free> loops_owner(&loops);
        std::printf("%.17g\n", loops.nminor ? loops.minor[0].area : 0.0);
        return 0;
    } catch (const std::exception &e) {
        std::fprintf(stderr, "minor_loop_area: %s\n", e.what());
        return 2;
    }
}
