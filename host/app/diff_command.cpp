// `vitrum diff A B`: how far two images are apart.
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "app/arguments.h"
#include "app/commands.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "image/image_diff.h"
#include "image/image.h"

namespace vitrum {

int diffCommand(int argc, char** argv, int first) {
    if (wantsHelp(argc, argv, first)) {
        std::cout << "usage: vitrum diff A B [--heatmap OUT.png] [--scale S]\n\n"
                     "Compares two images of the same size channel by channel on linear values (PNG is decoded\n"
                     "from sRGB) and prints RMSE, PSNR, the largest and mean absolute error and the share of\n"
                     "pixels whose largest channel error is over 1/255 and over 0.05. --heatmap writes the\n"
                     "per-pixel error as black-red-yellow-white, white at S (default 0.1).\n";
        return 0;
    }
    Arguments args(argc, argv, first);
    std::vector<std::string> images;
    std::string heatmap;
    float scale = 0.1f;
    while (!args.empty()) {
        std::string a = args.next();
        if (a == "--heatmap") heatmap = args.valueOf(a);
        else if (a == "--scale") {
            scale = Arguments::toFloat(a, args.valueOf(a));
            if (scale <= 0) throw InputError("--scale must be positive");
        } else if (a.rfind("--", 0) == 0) throw InputError("unknown option " + a + " (see vitrum diff --help)");
        else images.push_back(a);
    }
    if (images.size() != 2) throw InputError("diff needs two images (see vitrum diff --help)");
    if (!heatmap.empty())
        for (const std::string& image : images) checkNotAnInput(heatmap, image, "an image compared");
    Image a = readImage(images[0]);
    Image b = readImage(images[1]);
    ImageDiff d = diffImages(a, b);
    std::printf("rmse: %.6g\npsnr: %.2f dB\nmax abs error: %.6g\nmean abs error: %.6g\n", d.rmse, d.psnr,
                d.maxAbsError, d.meanAbsError);
    std::printf("pixels over 1/255: %.4f%%\npixels over 0.05: %.4f%%\n", 100.0 * d.shareOver1of255,
                100.0 * d.shareOver005);
    if (!heatmap.empty()) writeImage(diffHeatMap(a, b, scale), heatmap);
    return 0;
}

}  // namespace vitrum
