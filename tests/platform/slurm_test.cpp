// A sweep on a Slurm cluster end to end: the test brings up a one-node cluster on this machine
// (tests/slurm/cluster.sh: slurmctld, slurmd and munged as root, on ports of their own),
// `surfvp sweep --slurm 2` submits a job array of two shards and a merge after it, and the
// merged results are those of the same sweep run here. If the cluster cannot start, the test
// fails with the reason.
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <thread>

#include "cli.h"

namespace surfvp::test {
namespace {
namespace fs = std::filesystem;
using Json = nlohmann::json;

const std::string kCluster = std::string(SURFVP_SOURCE_DIR) + "/tests/slurm/cluster.sh";

// Starts the cluster; stops it when the test ends, however it ends.
class Cluster {
public:
    explicit Cluster(const std::string& dir) : dir_(dir) {
        fs::create_directories(dir);
        const std::string log = dir + "/start.log";
        started_ = std::system((kCluster + " start " + dir + " >" + log + " 2>&1").c_str()) == 0;
        why_ = slurp(log);
        setenv("SLURM_CONF", (dir + "/slurm.conf").c_str(), 1);
    }
    ~Cluster() {
        std::system((kCluster + " stop " + dir_ + " >/dev/null 2>&1").c_str());
        unsetenv("SLURM_CONF");
    }
    bool started() const { return started_; }
    const std::string& why() const { return why_; }

private:
    std::string dir_, why_;
    bool started_ = false;
};

Json points_of(const std::string& dir) {
    Json points = Json::parse(slurp(dir + "/results.json"))["points"];
    for (auto& p : points) p.erase("wall_s");
    return points;
}

TEST(Slurm, ASweepAsAJobArrayGivesTheResultsOfOneRunHere) {
    const std::string dir = fresh_dir("slurm");
    const std::string sweep =
        write_file(dir, "sweep.yaml",
                   "scenario: " + kBudget +
                       "\n"
                       "set: {surf.frames: 3, surf.width: 256, surf.height: 192, surf.target_keypoints: 20}\n"
                       "axes:\n  fhg.clock: [25 MHz, 50 MHz]\n  fhg.read_buses: [2, 4]\n");
    Cluster cluster(dir + "/cluster");
    ASSERT_TRUE(cluster.started()) << "the one-node Slurm cluster did not start:\n" << cluster.why();
    const auto submitted = surfvp("sweep " + sweep + " --slurm 2 --jobs 1 --out " + dir + "/cluster_out");
    ASSERT_EQ(submitted.exit_code, 0) << submitted.err;
    EXPECT_NE(submitted.err.find("job array"), std::string::npos) << submitted.err;
    EXPECT_TRUE(fs::exists(dir + "/cluster_out/slurm/array.sh"));
    // The merge job writes results.json once both shards have ended.
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(3);
    while (!fs::exists(dir + "/cluster_out/results.json") && std::chrono::steady_clock::now() < deadline)
        std::this_thread::sleep_for(std::chrono::milliseconds(250));
    ASSERT_TRUE(fs::exists(dir + "/cluster_out/results.json"))
        << "no results after 3 minutes; shard 1's log:\n"
        << slurp(dir + "/cluster_out/slurm/shard-1.log") << "\nmerge log:\n"
        << slurp(dir + "/cluster_out/slurm/merge.log");
    EXPECT_TRUE(fs::exists(dir + "/cluster_out/shard-1-of-2.db"));
    EXPECT_TRUE(fs::exists(dir + "/cluster_out/shard-2-of-2.db"));
    ASSERT_EQ(surfvp("sweep " + sweep + " --quiet --out " + dir + "/here").exit_code, 0);
    EXPECT_EQ(points_of(dir + "/cluster_out"), points_of(dir + "/here"));
}

}  // namespace
}  // namespace surfvp::test
