// report.html as a reader's tool sees it: well-formed XML, self-contained, and each chart
// carrying the run's own figures (report.json's).
#include <gtest/gtest.h>
#include <libxml/parser.h>
#include <libxml/xpath.h>
#include <libxml/xpathInternals.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "cli.h"

namespace surfvp::test {
namespace {

// The XHTML parsed as XML, queried by XPath over the XHTML and SVG namespaces.
class Page {
public:
    explicit Page(const std::string& html)
        : doc_(xmlReadMemory(html.data(), int(html.size()), "report.html", nullptr, XML_PARSE_NONET), xmlFreeDoc) {}
    bool ok() const { return doc_ != nullptr; }
    std::vector<xmlNodePtr> all(const std::string& xpath) const {
        std::unique_ptr<xmlXPathContext, decltype(&xmlXPathFreeContext)> ctx(xmlXPathNewContext(doc_.get()),
                                                                             xmlXPathFreeContext);
        xmlXPathRegisterNs(ctx.get(), BAD_CAST "h", BAD_CAST "http://www.w3.org/1999/xhtml");
        xmlXPathRegisterNs(ctx.get(), BAD_CAST "s", BAD_CAST "http://www.w3.org/2000/svg");
        std::unique_ptr<xmlXPathObject, decltype(&xmlXPathFreeObject)> found(
            xmlXPathEvalExpression(BAD_CAST xpath.c_str(), ctx.get()), xmlXPathFreeObject);
        std::vector<xmlNodePtr> nodes;
        if (found && found->nodesetval)
            for (int i = 0; i < found->nodesetval->nodeNr; ++i) nodes.push_back(found->nodesetval->nodeTab[i]);
        return nodes;
    }
    static std::string attr(xmlNodePtr node, const char* name) {
        xmlChar* v = xmlGetProp(node, BAD_CAST name);
        std::string s = v ? reinterpret_cast<const char*>(v) : "";
        xmlFree(v);
        return s;
    }

private:
    std::unique_ptr<xmlDoc, decltype(&xmlFreeDoc)> doc_;
};

TEST(ReportHtml, SelfContainedChartsCarryTheRunsFigures) {
    const std::string out = fresh_dir("html");
    ASSERT_EQ(surfvp("run " + kBudget + " --trace none --quiet --out " + out + kOneRun +
                     " --set surf.frames=3 --set surf.width=512 --set surf.height=384 --set budget.fps=0")
                  .exit_code,
              0);
    const auto r = nlohmann::json::parse(slurp(out + "/report.json"));
    const Page page(slurp(out + "/report.html"));
    ASSERT_TRUE(page.ok()) << "report.html is not well-formed XML";
    EXPECT_TRUE(page.all("//h:script").empty());
    for (xmlNodePtr n : page.all("//*[@href or @src]"))  // nothing from outside the file
        EXPECT_EQ((Page::attr(n, "href") + Page::attr(n, "src")).rfind("data:", 0), 0u);

    // The Gantt: IIG, FHG and descriptors of each of the 3 frames, at the per-frame times.
    const auto tasks = page.all("//s:svg[@id='gantt']/s:rect[@class='task']");
    ASSERT_EQ(tasks.size(), 9u);
    const auto frame1 = page.all("//s:svg[@id='gantt']/s:rect[@class='task'][@data-frame='1']");
    ASSERT_EQ(frame1.size(), 3u);
    EXPECT_NEAR(std::stod(Page::attr(frame1[0], "data-start-ms")),
                r["workload"]["per_frame"][1]["start_ms"].get<double>(), 1e-3);
    EXPECT_NEAR(std::stod(Page::attr(frame1[1], "data-end-ms")),
                r["workload"]["per_frame"][1]["determinants_done_ms"].get<double>(), 1e-3);

    // Busy, waits, idle per resource: the FHG's busy time is the report's.
    const auto fhg_busy = page.all("//s:svg[@id='resources']/s:rect[@class='busy'][@data-resource='fhg']");
    ASSERT_EQ(fhg_busy.size(), 1u);
    EXPECT_NEAR(std::stod(Page::attr(fhg_busy[0], "data-ms")), r["time_per_frame"]["fhg"]["busy_ms"].get<double>(),
                1e-3);

    // Utilisation and FIFO levels over time: the series' own peaks and lengths.
    const auto& write = r["buses"]["plb2"]["write"]["busy_series"]["values"];
    double peak = 0;
    for (const auto& v : write) peak = std::max(peak, v.get<double>());
    const auto plb2 = page.all("//s:svg[@id='buses']/s:polyline[@data-name='plb2 write']");
    ASSERT_EQ(plb2.size(), 1u);
    EXPECT_NEAR(std::stod(Page::attr(plb2[0], "data-peak")), peak, 1e-4);
    EXPECT_EQ(std::stoul(Page::attr(plb2[0], "data-bins")), write.size());
    const auto maxima = page.all("//s:svg[@id='maxima_fifo']/s:polyline");
    ASSERT_EQ(maxima.size(), 1u);
    EXPECT_EQ(std::stoul(Page::attr(maxima[0], "data-peak")), r["fhg"]["maxima_fifo_high_water"].get<uint64_t>());

    // The keypoints of frame 0 on its picture.
    EXPECT_EQ(page.all("//s:svg[@id='keypoints']/s:circle[@class='keypoint']").size(),
              r["workload"]["per_frame"][0]["keypoints"].get<size_t>());
    EXPECT_EQ(page.all("//s:svg[@id='keypoints']/s:image").size(), 1u);
}

}  // namespace
}  // namespace surfvp::test
