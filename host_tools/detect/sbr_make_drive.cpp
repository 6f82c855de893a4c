// SPDX-License-Identifier: MIT
// sbr_make_drive: a short drive as a video file, made from one recorded frame by the
// camera moving towards the image centre (a zoom that grows each frame, so the scene's
// signs grow and move outwards as when a car approaches them). The tests make their video
// with it at set-up time; no video is kept in the repository.
//
//   sbr_make_drive --image FRAME --out drive.avi [--frames 30] [--fps 10] [--zoom 1.9]
//
// The container and codec follow the extension: .avi (MJPG) or .mp4 (mp4v).
#include "cli_core.hpp"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include <cstdio>
#include <string>

int main(int argc, char **argv) {
    std::string image, out;
    int frames = 30;
    double fps = 10.0, zoom = 1.9;
    CLI::App app{"sbr_make_drive: a short drive as a video, made from one recorded frame (a camera moving forward)"};
    app.add_option("--image", image, "the recorded frame")->required()->check(CLI::ExistingFile);
    app.add_option("--out", out, "the video to write (.avi: MJPG, .mp4: mp4v)")->required();
    app.add_option("--frames", frames, "frames")->check(CLI::Range(2, 10000))->capture_default_str();
    app.add_option("--fps", fps, "frames per second")->check(CLI::Range(1.0, 120.0))->capture_default_str();
    app.add_option("--zoom", zoom, "magnification of the last frame")->check(CLI::Range(1.0, 8.0))->capture_default_str();
    const int parsed = sbr_host::parse_cli(app, argc, argv);
    if (parsed >= 0) return parsed;
    const cv::Mat img = cv::imread(image, cv::IMREAD_COLOR);
    if (img.empty()) {
        std::fprintf(stderr, "sbr_make_drive: --image %s: cannot decode it\n", image.c_str());
        return 2;
    }
    const bool avi = out.size() > 4 && out.compare(out.size() - 4, 4, ".avi") == 0;
    cv::VideoWriter w(out, cv::CAP_FFMPEG, avi ? cv::VideoWriter::fourcc('M', 'J', 'P', 'G')
                                               : cv::VideoWriter::fourcc('m', 'p', '4', 'v'),
                      fps, img.size());
    if (!w.isOpened()) {
        std::fprintf(stderr, "sbr_make_drive: --out %s: cannot write a video there\n", out.c_str());
        return 1;
    }
    const cv::Point2f c(0.5f * float(img.cols), 0.5f * float(img.rows));
    for (int k = 0; k < frames; ++k) {
        const double s = 1.0 + (zoom - 1.0) * double(k) / double(frames - 1);
        // the view of the frame magnified s times about its centre
        cv::Mat m = (cv::Mat_<double>(2, 3) << s, 0.0, double(c.x) * (1.0 - s), 0.0, s, double(c.y) * (1.0 - s));
        cv::Mat f;
        cv::warpAffine(img, f, m, img.size(), cv::INTER_LINEAR, cv::BORDER_REPLICATE);
        w.write(f);
    }
    w.release();
    std::printf("sbr_make_drive: %d frames of %d x %d at %.1f fps -> %s\n", frames, img.cols, img.rows, fps,
                out.c_str());
    return 0;
}
