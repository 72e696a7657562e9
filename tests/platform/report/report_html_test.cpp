// report.html as a reader's tool sees it: well-formed XML, self-contained, and each chart
// carrying the run's own figures (report.json's).
#include <gtest/gtest.h>
#include <libxml/parser.h>
#include <libxml/xpath.h>
#include <libxml/xpathInternals.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
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
    // Nothing from outside the file: pictures inline, links only to the page's own sections and
    // to the run's own files beside it.
    for (xmlNodePtr n : page.all("//*[@src]")) EXPECT_EQ(Page::attr(n, "src").rfind("data:", 0), 0u);
    for (xmlNodePtr n : page.all("//*[@href]")) {
        const std::string href = Page::attr(n, "href");
        if (href.rfind("data:", 0) == 0 || href.rfind("#", 0) == 0) continue;
        EXPECT_TRUE(std::filesystem::exists(out + "/" + href)) << href;
        EXPECT_EQ(href.find(".."), std::string::npos) << href;
    }

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

// The review: sections in the order a review reads them, each with the run's own figures;
// charts that follow the window with round ticks and a legend for every colour they draw.
TEST(ReportHtml, TheReviewPageCarriesTheVerdictItsDoubtAndWhatCanChange) {
    const std::string out = fresh_dir("html_review");
    const auto run = surfvp("run " + kBudget +
                            " --trace none --quiet --set surf.frames=4 --set surf.width=512 --set surf.height=384 "
                            "--set verdict.samples=20 --set budget.fps=12 --out " +
                            out);
    ASSERT_LE(run.exit_code, 1) << run.err;
    const auto r = nlohmann::json::parse(slurp(out + "/report.json"));
    const auto& v = r["verdict"];
    const Page page(slurp(out + "/report.html"));
    ASSERT_TRUE(page.ok());

    std::vector<std::string> order;
    for (xmlNodePtr s : page.all("//h:section")) order.push_back(Page::attr(s, "id"));
    EXPECT_EQ(order, (std::vector<std::string>{"verdict", "doubt", "changes", "correlation", "costs", "timeline",
                                               "resources", "buses", "fifos", "keypoints", "outputs"}));
    auto text = [&](const std::string& xpath) {
        const auto nodes = page.all(xpath);
        if (nodes.empty()) return std::string();
        xmlChar* t = xmlNodeGetContent(nodes[0]);
        std::string s = reinterpret_cast<const char*>(t);
        xmlFree(t);
        return s;
    };
    // The verdict: the statement, and each break-even with its value.
    EXPECT_NE(text("//h:section[@id='verdict']/h:p[1]").find(v["statement"].get<std::string>()), std::string::npos);
    ASSERT_FALSE(v["break_even"].empty());
    EXPECT_EQ(page.all("//h:table[@id='break_even']/h:tr").size(), v["break_even"].size() + 1);
    EXPECT_NE(text("//h:table[@id='break_even']").find(v["break_even"][0]["value"].get<std::string>()),
              std::string::npos);
    EXPECT_EQ(page.all("//h:table[@id='chain']/h:tr").size(), v["chain"].size() + 1);
    // How sure: the band, the tornado, the joint distribution.
    const auto band = page.all("//h:p[@id='band']");
    ASSERT_EQ(band.size(), 1u);
    EXPECT_NEAR(std::stod(Page::attr(band[0], "data-low")), v["band"]["low_fps"].get<double>(), 1e-4);
    EXPECT_FALSE(page.all("//h:section[@id='doubt']//s:svg").empty());
    const auto joint = page.all("//s:svg[@id='distribution']/s:rect[@class='band']");
    ASSERT_EQ(joint.size(), 1u);
    EXPECT_NEAR(std::stod(Page::attr(joint[0], "data-p95")), v["doubt"]["fps"]["p95"].get<double>(), 1e-4);
    // What you can change: every design choice and software setting the verdict tried.
    EXPECT_EQ(page.all("//h:table[@id='design_choices']/h:tr").size(), v["changes"]["axes"].size() + 1);
    EXPECT_EQ(page.all("//h:table[@id='software']/h:tr").size(), v["software"].size() + 1);
    // Resources and power: the device's shares and the watts against the budget.
    const auto bram = page.all("//s:svg[@id='costs']/s:rect[@data-name='ramb36']");
    ASSERT_EQ(bram.size(), 1u);
    EXPECT_NEAR(std::stod(Page::attr(bram[0], "data-share")), r["fpga_resources"]["share"]["ramb36"].get<double>(),
                1e-4);
    const auto power = page.all("//s:svg[@id='costs']/s:rect[@data-name='power']");
    ASSERT_EQ(power.size(), 1u);
    EXPECT_NEAR(std::stod(Page::attr(power[0], "data-share")),
                r["power"]["watts"].get<double>() / r["power"]["budget_w"].get<double>(), 1e-4);
    // Every other output linked (the keypoint files as one).
    for (const auto& o : r["outputs"]) {
        const std::string f = o;
        if (f == "report.html" || (f.rfind("keypoints/", 0) == 0 && f != "keypoints/frame_0000.surf")) continue;
        EXPECT_EQ(page.all("//h:section[@id='outputs']//h:a[@href='" + f + "']").size(), 1u) << f;
    }

    for (xmlNodePtr svg : page.all("//s:svg[@class='chart']")) {
        const std::string id = Page::attr(svg, "id");
        EXPECT_EQ(Page::attr(svg, "width"), "100%") << id;  // follows the window
        EXPECT_FALSE(Page::attr(svg, "viewBox").empty()) << id;
        // Ticks at round numbers: equally spaced by 1, 2 or 5 times a power of ten.
        std::vector<double> ticks;
        for (xmlNodePtr t : page.all("//s:svg[@id='" + id + "']/s:text[@class='tick']")) {
            xmlChar* c = xmlNodeGetContent(t);
            ticks.push_back(std::stod(reinterpret_cast<const char*>(c)));
            xmlFree(c);
        }
        std::sort(ticks.begin(), ticks.end());
        ticks.erase(std::unique(ticks.begin(), ticks.end()), ticks.end());
        ASSERT_GE(ticks.size(), 2u) << id;
        const double step = ticks[1] - ticks[0], mantissa = step / std::pow(10.0, std::floor(std::log10(step)));
        EXPECT_TRUE(std::abs(mantissa - 1) < 1e-6 || std::abs(mantissa - 2) < 1e-6 || std::abs(mantissa - 5) < 1e-6)
            << id << ": step " << step;
        // Every colour a bar or line is drawn in is named in the legend.
        std::set<std::string> legend;
        for (xmlNodePtr k : page.all("//s:svg[@id='" + id + "']/s:g[@class='legend']/s:rect"))
            legend.insert(Page::attr(k, "fill"));
        for (xmlNodePtr d : page.all("//s:svg[@id='" + id + "']/s:rect[@class]")) {
            const std::string fill = Page::attr(d, "fill");
            EXPECT_TRUE(legend.count(fill)) << id << ": " << fill << " has no legend";
        }
        for (xmlNodePtr d : page.all("//s:svg[@id='" + id + "']/s:polyline"))
            EXPECT_TRUE(legend.count(Page::attr(d, "stroke"))) << id;
    }
}

}  // namespace
}  // namespace surfvp::test
