// Sequences from an image folder (visp-images-data's castle), a list file, and a video
// (opencv-doc's vtest.avi).
#include "sw/eval/sequence.h"

#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "sw/eval/eval_test_support.h"

namespace surfvp::eval {
namespace {

const std::filesystem::path kCastleImages = std::filesystem::path(VISP_DATA_DIR) / "mbt-depth/Castle-simu/Images";
const std::filesystem::path kVideo = std::filesystem::path(OPENCV_DATA_DIR) / "vtest.avi";

TEST(Sequence, ImageFolderIsSortedByName) {
    ASSERT_TRUE(test::package_file(kCastleImages / "Image_0001.pgm", "visp-images-data"));
    Sequence s = open_sequence(kCastleImages);
    EXPECT_EQ(s.kind, SequenceKind::image_folder);
    ASSERT_EQ(s.frames.size(), 40u);
    for (std::size_t i = 0; i < s.frames.size(); ++i) {
        char name[32];
        std::snprintf(name, sizeof name, "Image_%04zu.pgm", i + 1);
        EXPECT_EQ(s.frames[i].name, name);
        EXPECT_EQ(s.frames[i].index, i);
    }
    Sequence limited = open_sequence(kCastleImages, 5);
    ASSERT_EQ(limited.frames.size(), 5u);
    SequenceReader reader(limited);
    cv::Mat image;
    std::size_t read = 0;
    while (reader.next(image)) {
        EXPECT_EQ(image.size(), cv::Size(640, 480));
        EXPECT_EQ(image.type(), CV_8UC1);
        ++read;
    }
    EXPECT_EQ(read, 5u);
}

TEST(Sequence, ListFileKeepsItsOrderAndResolvesRelativePaths) {
    ASSERT_TRUE(test::package_file(kCastleImages / "Image_0007.pgm", "visp-images-data"));
    test::TemporaryFolder dir;
    std::filesystem::create_directories(dir / "frames");
    std::filesystem::copy_file(kCastleImages / "Image_0002.pgm", dir / "frames/second frame.pgm");
    std::ofstream(dir / "list.txt") << "# castle, out of order\n"
                                    << (kCastleImages / "Image_0007.pgm").string() << "\n"
                                    << "\n"
                                    << "  frames/second frame.pgm   # relative to the list\n"
                                    << (kCastleImages / "Image_0003.pgm").string() << "\n";
    Sequence s = open_sequence(dir / "list.txt");
    EXPECT_EQ(s.kind, SequenceKind::image_list);
    ASSERT_EQ(s.frames.size(), 3u);
    EXPECT_EQ(s.frames[0].name, "Image_0007.pgm");
    EXPECT_EQ(s.frames[1].image, dir / "frames/second frame.pgm");
    EXPECT_EQ(s.frames[2].name, "Image_0003.pgm");
    EXPECT_EQ(open_sequence(dir / "list.txt", 2).frames.size(), 2u);
    SequenceReader reader(s);
    cv::Mat image;
    ASSERT_TRUE(reader.next(image));
    ASSERT_TRUE(reader.next(image));
    cv::Mat original = cv::imread((kCastleImages / "Image_0002.pgm").string(), cv::IMREAD_GRAYSCALE);
    EXPECT_EQ(cv::norm(image, original, cv::NORM_INF), 0.0);
}

TEST(Sequence, ListFileNamesTheLineOfAMissingImage) {
    test::TemporaryFolder dir;
    std::ofstream(dir / "list.txt") << "# nothing yet\n\nmissing.png\n";
    try {
        open_sequence(dir / "list.txt");
        ADD_FAILURE() << "no FormatError";
    } catch (const FormatError& e) {
        EXPECT_EQ(e.file(), dir / "list.txt");
        EXPECT_EQ(e.line(), 3u);
        EXPECT_NE(e.problem().find("missing.png' does not exist"), std::string::npos) << e.what();
    }
}

TEST(Sequence, VideoWithAFrameLimit) {
    ASSERT_TRUE(test::package_file(kVideo, "opencv-doc"));
    Sequence s = open_sequence(kVideo, 12);
    EXPECT_EQ(s.kind, SequenceKind::video);
    ASSERT_EQ(s.frames.size(), 12u);
    EXPECT_EQ(s.frames[0].name, "vtest.avi#0");
    EXPECT_EQ(s.frames[11].name, "vtest.avi#11");
    EXPECT_TRUE(s.frames[3].image.empty());
    SequenceReader reader(s);
    cv::Mat image, first;
    std::size_t read = 0;
    while (reader.next(image)) {
        EXPECT_EQ(image.size(), cv::Size(768, 576));
        EXPECT_EQ(image.type(), CV_8UC1);
        if (read == 0) first = image.clone();
        ++read;
    }
    EXPECT_EQ(read, 12u);
    EXPECT_GT(cv::norm(image, first, cv::NORM_L1), 0.0);  // the frames differ: people walk
    SequenceReader colour(s, cv::IMREAD_COLOR);
    ASSERT_TRUE(colour.next(image));
    EXPECT_EQ(image.type(), CV_8UC3);
}

TEST(Sequence, ErrorsNameTheSource) {
    test::TemporaryFolder dir;
    std::ofstream(dir / "notes.dat") << "not a video\n";
    std::filesystem::create_directories(dir / "empty");
    std::ofstream(dir / "empty.lst") << "# no images\n";
    struct Case {
        std::filesystem::path source;
        const char* problem;
    };
    for (const Case& c :
         {Case{dir / "absent", "no such file or folder"}, Case{dir / "notes.dat", "not a folder, an image list"},
          Case{dir / "empty", "no image files"}, Case{dir / "empty.lst", "names no image"}}) {
        SCOPED_TRACE(c.source.string());
        try {
            open_sequence(c.source);
            ADD_FAILURE() << "no error";
        } catch (const std::runtime_error& e) {
            std::string what = e.what();
            EXPECT_NE(what.find(c.source.string()), std::string::npos) << what;
            EXPECT_NE(what.find(c.problem), std::string::npos) << what;
        }
    }
}

}  // namespace
}  // namespace surfvp::eval
