// photon-image-diff: compares two 8-bit images (PNG) channel by channel, for tests that check
// what a program showed against what another wrote.
//   photon-image-diff a.png b.png [--max-rmse X] [--max-abs N]
// Prints the size, the RMSE and the largest difference in 8-bit steps, and how many channel
// values differ at all. Exit 0 if the sizes match and both limits hold, 1 if not, 2 on bad input.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include <stb_image.h>

int main(int argc, char** argv) {
    if (argc < 3) {
        std::fprintf(stderr, "usage: photon-image-diff a.png b.png [--max-rmse X] [--max-abs N]\n");
        return 2;
    }
    double maxRmse = -1.0;
    int maxAbs = -1;
    for (int i = 3; i + 1 < argc; i += 2) {
        if (std::strcmp(argv[i], "--max-rmse") == 0) {
            maxRmse = std::atof(argv[i + 1]);
        } else if (std::strcmp(argv[i], "--max-abs") == 0) {
            maxAbs = std::atoi(argv[i + 1]);
        } else {
            std::fprintf(stderr, "photon-image-diff: unknown option %s\n", argv[i]);
            return 2;
        }
    }
    int w[2] = {};
    int h[2] = {};
    int channels = 0;
    unsigned char* pixels[2] = {};
    for (int k = 0; k < 2; ++k) {
        pixels[k] = stbi_load(argv[1 + k], &w[k], &h[k], &channels, 3);
        if (pixels[k] == nullptr) {
            std::fprintf(stderr, "photon-image-diff: %s: %s\n", argv[1 + k], stbi_failure_reason());
            return 2;
        }
    }
    if (w[0] != w[1] || h[0] != h[1]) {
        std::printf("sizes differ: %dx%d and %dx%d\n", w[0], h[0], w[1], h[1]);
        return 1;
    }
    std::size_t n = std::size_t(w[0]) * h[0] * 3;
    double sum = 0.0;
    int largest = 0;
    std::size_t differing = 0;
    for (std::size_t i = 0; i < n; ++i) {
        int d = std::abs(int(pixels[0][i]) - int(pixels[1][i]));
        sum += double(d) * d;
        largest = d > largest ? d : largest;
        differing += d != 0 ? 1 : 0;
    }
    double rmse = std::sqrt(sum / double(n));
    std::printf("%dx%d: RMSE %.4f, largest difference %d, %zu of %zu values differ\n", w[0], h[0], rmse, largest,
                differing, n);
    stbi_image_free(pixels[0]);
    stbi_image_free(pixels[1]);
    bool ok = (maxRmse < 0.0 || rmse <= maxRmse) && (maxAbs < 0 || largest <= maxAbs);
    return ok ? 0 : 1;
}
