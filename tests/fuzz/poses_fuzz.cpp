// Fuzz target: the camera-pose reader (sw/eval/pose_geometry.h: read_pose_file), ViSP's
// CameraPose/Camera_NNN.txt: four lines of four numbers, a rigid transform cMo.
//
// Input: the file's bytes.
//
// Expected answer to a malformed file: FormatError. Any other exception, a crash or a
// sanitizer report is a bug, and so is a pose the reader returns that is not what it
// promised: finite, the last row 0 0 0 1 (to 1e-9), the rotation orthonormal (to the reader's 1e-5;
// checked here at 1e-4) with determinant +1.
#include <Eigen/Dense>
#include <string>

#include "fuzz_support.h"
#include "sw/eval/pose_geometry.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace surfvp;
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    const std::filesystem::path file = fuzz::write_scratch("Camera_000.txt", bytes);
    try {
        const Eigen::Matrix4d m = eval::read_pose_file(file);
        if (!m.allFinite()) fuzz::bug("the reader returned a non-finite pose");
        if (!((m.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).cwiseAbs().maxCoeff() <= 1e-9))
            fuzz::bug("the pose's last row is not 0 0 0 1");
        const Eigen::Matrix3d r = m.topLeftCorner<3, 3>();
        if (!((r * r.transpose() - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() < 1e-4) ||
            !(std::abs(r.determinant() - 1) < 1e-4))
            fuzz::bug("the pose's rotation is not a rotation");
    } catch (const eval::FormatError&) {
        // the reader's answer to a malformed file
    } catch (const std::exception& e) {
        fuzz::unexpected(e);
    }
    return 0;
}
