/* SPDX-License-Identifier: Apache-2.0 */
/* Minimal use of afn's C API: denoise a small synthetic frame sequence with one filter. */
#include <afn/afn.h>

#include <stdio.h>
#include <stdlib.h>

int main(int argc, char** argv)
{
    const char* method = argc > 1 ? argv[1] : "identity";
    enum { W = 64, H = 36, FRAMES = 4 };
    static float color[W * H * 3], albedo[W * H * 3], output[W * H * 3];

    AFNDevice device = afnNewDevice(AFN_DEVICE_TYPE_DEFAULT);
    afnCommitDevice(device);
    AFNFilter filter = afnNewFilter(device, method);
    const char* message = NULL;
    if (afnGetDeviceError(device, &message) != AFN_ERROR_NONE) {
        fprintf(stderr, "afn error: %s\n", message);
        afnReleaseDevice(device);
        return 1;
    }
    afnSetFilterImage(filter, "color", color, AFN_FORMAT_FLOAT3, W, H, 0, 0, 0);
    afnSetFilterImage(filter, "albedo", albedo, AFN_FORMAT_FLOAT3, W, H, 0, 0, 0);
    afnSetFilterImage(filter, "output", output, AFN_FORMAT_FLOAT3, W, H, 0, 0, 0);
    afnCommitFilter(filter);

    srand(1);
    for (int frame = 0; frame < FRAMES; ++frame) {
        for (int i = 0; i < W * H * 3; ++i) {
            albedo[i] = 0.5f;
            color[i] = 0.5f * (float)rand() / (float)RAND_MAX; /* noisy 1-spp-like values */
        }
        afnExecuteFilter(filter);
        if (afnGetDeviceError(device, &message) != AFN_ERROR_NONE) {
            fprintf(stderr, "afn error: %s\n", message);
            break;
        }
        printf("frame %d: output[0] = %.4f %.4f %.4f\n", frame, output[0], output[1], output[2]);
    }
    afnReleaseFilter(filter);
    afnReleaseDevice(device);
    return 0;
}
