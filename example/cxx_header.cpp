// The C header compiled as C++ (extern "C" guards) and linked: an "exact" convolver of the
// paper's mass-spring pushed with a unit step force for 0.5 s; its displacement must reach
// the static deflection F/K = 1e-6 m to within 1 %.
#include <greenconv.h>

#include <cmath>
#include <cstdio>

int main()
{
    gc_convolver *conv = nullptr;
    char message[256];
    if (gc_convolver_new_sdof(1.0, 1.0e6, 0.02, 1.0e-4, "exact", 5000, &conv, message, sizeof message) != GC_OK) {
        std::fprintf(stderr, "cxx_header: %s\n", message);
        return 1;
    }
    double u_h = 0.0, w0 = 0.0;
    gc_convolver_instant_weight(conv, &w0);
    for (int n = 0; n < 5000; n++) {
        gc_convolver_history(conv, &u_h);
        gc_convolver_push(conv, 1.0);
    }
    const double u = u_h + w0 * 1.0;
    gc_convolver_delete(&conv);
    const bool ok = std::fabs(u - 1.0e-6) < 1.0e-8;
    std::printf("cxx_header: C++ build of greenconv.h ok; step response after 0.5 s: %.6e m (F/K = 1e-6 m): %s\n", u,
                ok ? "ok" : "MISMATCH");
    return ok ? 0 : 1;
}
