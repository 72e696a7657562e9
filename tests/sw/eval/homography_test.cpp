// Homography files: OpenCV FileStorage (opencv-doc's H1to3p.xml) and Oxford plain text.
#include "sw/eval/homography.h"

#include <fstream>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <algorithm>
#include <opencv2/core.hpp>

#include "sw/eval/eval_test_support.h"

namespace surfvp::eval {
namespace {

TEST(Homography, ReadsOpenCvsGraffitiFileStorage) {
    const std::string file = std::string(OPENCV_DATA_DIR) + "/H1to3p.xml";
    ASSERT_TRUE(test::package_file(file, "opencv-doc"));
    Eigen::Matrix3d h = read_homography_file(file);
    EXPECT_EQ(h(0, 0), 7.6285898e-01);
    EXPECT_EQ(h(0, 2), 2.2567123e+02);
    EXPECT_EQ(h(1, 2), -7.6999973e+01);
    EXPECT_EQ(h(2, 0), 3.4663091e-04);
    EXPECT_EQ(h(2, 2), 1.0);
}

TEST(Homography, ReadsOxfordPlainTextAndYaml) {
    test::TemporaryFolder dir;
    std::ofstream(dir / "H1to2p") << "   8.7976964e-01   3.1245438e-01  -3.9430589e+01\n"
                                     "  -1.8389418e-01   9.3847198e-01   1.5315784e+02\n"
                                     "   1.9641425e-04  -1.6015275e-05   1.0000000e+00\n";
    Eigen::Matrix3d h = read_homography_file(dir / "H1to2p");
    EXPECT_EQ(h(0, 1), 3.1245438e-01);
    EXPECT_EQ(h(1, 2), 1.5315784e+02);
    EXPECT_EQ(h(2, 1), -1.6015275e-05);
    cv::Mat m(3, 3, CV_64F);
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) m.at<double>(r, c) = h(r, c);
    {
        cv::FileStorage out((dir / "h.yml").string(), cv::FileStorage::WRITE);
        out << "size" << 3 << "H12" << m;
    }
    EXPECT_EQ(read_homography_file(dir / "h.yml"), h);  // the 3x3 node, not the scalar
}

TEST(Homography, MalformedFilesAreNamed) {
    test::TemporaryFolder dir;
    std::ofstream(dir / "two_rows") << "1 0 0\n0 1 0\n";
    std::ofstream(dir / "word") << "1 0 0\n0 one 0\n0 0 1\n";
    std::ofstream(dir / "singular") << "1 2 3\n2 4 6\n0 0 1\n";
    std::ofstream(dir / "no_matrix.xml") << "<?xml version=\"1.0\"?>\n<opencv_storage>\n"
                                            "<n>3</n>\n</opencv_storage>\n";
    struct Case {
        const char* file;
        std::size_t line;
        const char* problem;
    };
    for (const Case& c :
         {Case{"two_rows", 2, "file ends after 2 of the 3 rows"}, Case{"word", 2, "'one' is not a number"},
          Case{"singular", 0, "singular"}, Case{"no_matrix.xml", 0, "no 3x3 matrix"}}) {
        SCOPED_TRACE(c.file);
        try {
            read_homography_file(dir / c.file);
            ADD_FAILURE() << "no FormatError";
        } catch (const FormatError& e) {
            EXPECT_EQ(e.file(), dir / c.file);
            EXPECT_EQ(e.line(), c.line);
            EXPECT_NE(e.problem().find(c.problem), std::string::npos) << e.what();
        }
    }
    EXPECT_THROW(read_homography_file(dir / "absent"), std::runtime_error);
}

// Found by tests/fuzz (homography): OpenCV allocates rows x cols before reading the data, so
// a 300-byte file declaring a 100000 x 100000 matrix asked for 80 GB.
TEST(Homography, AHugeDeclaredMatrixIsSkippedNotAllocated) {
    test::TemporaryFolder dir;
    std::ofstream(dir / "huge.xml") << "<?xml version=\"1.0\"?>\n<opencv_storage>\n"
                                       "<H type_id=\"opencv-matrix\"><rows>100000</rows><cols>100000</cols>"
                                       "<dt>d</dt><data>1 0 0 0 1 0 0 0 1</data></H>\n</opencv_storage>\n";
    try {
        read_homography_file(dir / "huge.xml");
        ADD_FAILURE() << "no FormatError";
    } catch (const FormatError& e) {
        EXPECT_NE(e.problem().find("no 3x3 matrix"), std::string::npos) << e.what();
    }
}

// Found by tests/fuzz (homography): on this broken YAML, OpenCV 4.6's parser threw
// std::length_error, not cv::Exception, which escaped the reader as a bare exception. YAML is
// now read by yaml-cpp, which refuses it as well.
TEST(Homography, AFileOpenCvCannotParseIsAFormatError) {
    test::TemporaryFolder dir;
    std::ofstream(dir / "broken.yml") << "%YAML:1.0\n---\nH13: !!opencv-matrix\n   rows: 3\n   cols: 3\n   :td d\n"
                                         "5671230e+02, 3.3443473050e, 1.00000000e+00 ]\n";
    EXPECT_THROW(read_homography_file(dir / "broken.yml"), FormatError);
}

// Found by tests/fuzz (homography): OpenCV 4.6's XML parser crashes (a null pointer) on a NUL
// byte in the XML declaration; a file with a NUL byte is refused before OpenCV reads it.
TEST(Homography, AFileStorageWithANulByteIsAFormatError) {
    test::TemporaryFolder dir;
    const char xml[] = "<?xml version=\0\0\"1.0\"?>\n<opencv_storage>\n</opencv_storage>\n";
    std::ofstream(dir / "nul.xml", std::ios::binary) << std::string(xml, sizeof xml - 1);
    try {
        read_homography_file(dir / "nul.xml");
        ADD_FAILURE() << "no FormatError";
    } catch (const FormatError& e) {
        EXPECT_EQ(e.line(), 1u);
        EXPECT_NE(e.problem().find("a NUL byte"), std::string::npos) << e.what();
    }
}

// Found by tests/fuzz (homography): OpenCV 4.6's XML parser also crashes (a null pointer) on
// a file that ends after an attribute's '=', in the declaration or in a tag (spaces after it
// too); such a file is refused before OpenCV reads it.
TEST(Homography, AFileStorageEndingAfterAnAttributesEqualsSignIsAFormatError) {
    test::TemporaryFolder dir;
    for (const std::string xml :
         {"<?xml tersion=", "<?xml version= \n", "<?xml version=\"1.0\"?>\n<opencv_storage>\n<H x="}) {
        std::ofstream(dir / "cut.xml", std::ios::binary) << xml;
        try {
            read_homography_file(dir / "cut.xml");
            ADD_FAILURE() << "no FormatError for " << xml;
        } catch (const FormatError& e) {
            EXPECT_EQ(e.line(), xml.back() == '=' ? size_t(std::count(xml.begin(), xml.end(), '\n') + 1) : 1u) << xml;
            EXPECT_NE(e.problem().find("ends after an '='"), std::string::npos) << e.what();
        }
    }
}

// Found by tests/fuzz (homography): OpenCV 4.6's YAML parser never returns on this file, so
// YAML is read with yaml-cpp; the file is refused, at once.
TEST(Homography, AYamlFileOpenCvsParserHangsOnIsAFormatError) {
    test::TemporaryFolder dir;
    std::ofstream(dir / "hang.yml") << "%YAML:1.\n L:0\n--3-\n";
    EXPECT_THROW(read_homography_file(dir / "hang.yml"), FormatError);
}

// The YAML reader reads what OpenCV writes: the 3x3 node among others, a float matrix as
// OpenCV reads it (rounded to float), and names the line of an element that is no number.
TEST(Homography, YamlMatricesAsOpenCvWritesThem) {
    test::TemporaryFolder dir;
    cv::Mat f = (cv::Mat_<float>(3, 3) << 0.1f, 0, 5, 0, 1, 0, 0, 0, 1);
    cv::Mat wide = cv::Mat::eye(3, 4, CV_64F);
    {
        cv::FileStorage out((dir / "f.yml").string(), cv::FileStorage::WRITE);
        out << "wide" << wide << "Hf" << f;
    }
    const Eigen::Matrix3d h = read_homography_file(dir / "f.yml");
    EXPECT_EQ(h(0, 0), double(0.1f));
    EXPECT_EQ(h(0, 2), 5.0);
    std::ofstream(dir / "word.yml") << "%YAML:1.0\n---\nH: !!opencv-matrix\n   rows: 3\n   cols: 3\n   dt: d\n"
                                       "   data: [ 1, 0, 0,\n      0, one, 0, 0, 0, 1 ]\n";
    try {
        read_homography_file(dir / "word.yml");
        ADD_FAILURE() << "no FormatError";
    } catch (const FormatError& e) {
        EXPECT_EQ(e.line(), 8u);
        EXPECT_NE(e.problem().find("element 4 is not a number"), std::string::npos) << e.what();
    }
}

TEST(Homography, MapsPointsAndHasTheRightJacobian) {
    Eigen::Matrix3d t = translation_homography(5, -2);
    EXPECT_EQ(apply_homography(t, {1, 1}), Eigen::Vector2d(6, -1));
    EXPECT_EQ(homography_jacobian(t, {1, 1}), Eigen::Matrix2d::Identity());
    Eigen::Matrix3d h;
    h << 2, 0, 0, 0, 2, 0, 0.001, 0, 1;  // x' = 2x / (1 + x/1000)
    Eigen::Vector2d p(1000, 300);
    EXPECT_TRUE(apply_homography(h, p).isApprox(Eigen::Vector2d(1000, 300)));
    // d/dx 2x/(1 + x/1000) = 2 / (1 + x/1000)^2 = 0.5; d/dy of y' = -2y/1000/4 = -0.15.
    Eigen::Matrix2d j = homography_jacobian(h, p);
    EXPECT_NEAR(j(0, 0), 0.5, 1e-12);
    EXPECT_NEAR(j(0, 1), 0.0, 1e-12);
    EXPECT_NEAR(j(1, 0), -0.15, 1e-12);
    EXPECT_NEAR(j(1, 1), 1.0, 1e-12);
}

}  // namespace
}  // namespace surfvp::eval
