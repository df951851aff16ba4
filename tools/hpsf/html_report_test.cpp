// The HTML report's promises that need no browser: every string from a file is escaped, the page references
// nothing on the network, a golden check's many cases get a summary linking to each, the judged metric is marked,
// the metadata and extra tables say what they hold, large images are box-filtered down (and the page says so),
// and a failed write leaves nothing behind. That the page runs cleanly in a browser is
// tools/testing/html_report_chromium.cmake's test.
#include "tools/hpsf/html_report.h"

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "core/error.h"

namespace hpsf {
namespace {

ChannelImage Constant(int width, int height, float r, float g, float b) {
  ChannelImage image;
  image.path = "constant.exr";
  image.width = width;
  image.height = height;
  image.channels = {"R", "G", "B"};
  for (std::size_t p = 0; p < image.PixelCount(); ++p) image.values.insert(image.values.end(), {r, g, b});
  return image;
}

ReportEntry Entry(const std::string& title, const ChannelImage& a, const ChannelImage& b,
                  DiffThresholds thresholds = {}) {
  ComparisonOptions options;
  options.thresholds = thresholds;
  return ReportEntry{title, &a, &b, a.path, b.path, CompareImages(a, b, options), std::nullopt};
}

std::size_t Count(const std::string& text, const std::string& part) {
  std::size_t n = 0;
  for (std::size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + part.size())) ++n;
  return n;
}

TEST(HtmlReport, EscapesEveryStringFromTheFiles) {
  ChannelImage a = Constant(4, 4, 0.5f, 0.25f, 0.125f), b = Constant(4, 4, 0.5f, 0.25f, 0.25f);
  a.path = "dir/<img src=x onerror=alert(1)>.exr";
  a.metadata["scene"] = "<script>alert('scene')</script>";
  b.metadata["scene"] = "cornell & \"box\"";
  ReportEntry entry = Entry("<b>title</b>", a, b);
  entry.extra = nlohmann::json{{"<key>", "</table><script>alert(2)</script>"}};
  const std::string html = RenderHtmlReport("report <i>of</i> \"things\"", {entry});

  for (const char* raw : {"<script>alert", "<img src=x", "<b>title", "<i>of", "</table><script>", "<key>"}) {
    EXPECT_EQ(html.find(raw), std::string::npos) << raw << " reached the page unescaped";
  }
  EXPECT_NE(html.find("&lt;script&gt;alert(&#39;scene&#39;)&lt;/script&gt;"), std::string::npos);
  EXPECT_NE(html.find("cornell &amp; &quot;box&quot;"), std::string::npos);
  EXPECT_NE(html.find("dir/&lt;img src=x onerror=alert(1)&gt;.exr"), std::string::npos);
  EXPECT_NE(html.find("&lt;b&gt;title&lt;/b&gt;"), std::string::npos);
  EXPECT_NE(html.find("<title>report &lt;i&gt;of&lt;/i&gt; &quot;things&quot;</title>"), std::string::npos);
  // The page's own two scripts, and no other.
  EXPECT_EQ(Count(html, "<script>"), 2u);
}

TEST(HtmlReport, IsSelfContained) {
  const ChannelImage a = Constant(8, 8, 1, 1, 1), b = Constant(8, 8, 1, 1, 0.5f);
  const std::string html = RenderHtmlReport("self-contained", {Entry("case", a, b)});
  for (const char* reference : {"http:", "https:", "src=\"//", "href=\"//", "@import", "url("}) {
    EXPECT_EQ(html.find(reference), std::string::npos) << reference;
  }
  EXPECT_NE(html.find("src=\"data:image/png;base64,iVBORw0KGgo"), std::string::npos) << "the heatmap, as a PNG";
  EXPECT_EQ(Count(html, "data-pixels=\""), 2u) << "A and B";
}

TEST(HtmlReport, ManyCasesGetASummaryLinkingToEach) {
  const ChannelImage a = Constant(4, 4, 0.5f, 0.5f, 0.5f), near = Constant(4, 4, 0.5f, 0.5f, 0.55f),
                     far = Constant(4, 4, 0.5f, 0.5f, 0.9f);
  const DiffThresholds thresholds{DiffMetric::kMaxAbs, 0.01, 0.1};
  const std::string html = RenderHtmlReport(
      "golden",
      {Entry("same", a, a, thresholds), Entry("near", a, near, thresholds), Entry("far", a, far, thresholds)});
  EXPECT_NE(html.find("<table class=\"summary\">"), std::string::npos);
  for (const char* row :
       {"<a href=\"#case-1\">same</a>", "<a href=\"#case-2\">near</a>", "<a href=\"#case-3\">far</a>"}) {
    EXPECT_NE(html.find(row), std::string::npos) << row;
  }
  for (const char* section : {"id=\"case-1\"", "id=\"case-2\"", "id=\"case-3\""}) {
    EXPECT_NE(html.find(section), std::string::npos) << section;
  }
  EXPECT_NE(html.find("<span class=\"verdict fail\">1 FAIL</span>"), std::string::npos);
  EXPECT_NE(html.find("<span class=\"verdict warn\">1 WARN</span>"), std::string::npos);
  EXPECT_NE(html.find("<span class=\"verdict pass\">1 PASS</span>"), std::string::npos);
  EXPECT_NE(html.find("<td>max 0.05</td>"), std::string::npos) << "the judged metric in the summary";

  const std::string one = RenderHtmlReport("one", {Entry("alone", a, near)});
  EXPECT_EQ(one.find("<table class=\"summary\">"), std::string::npos) << "one case needs no summary";
}

TEST(HtmlReport, MarksTheJudgedMetricAndListsEveryOther) {
  const ChannelImage a = Constant(8, 8, 0.5f, 0.5f, 0.5f), b = Constant(8, 8, 0.5f, 0.5f, 0.6f);
  const std::string html = RenderHtmlReport("psnr", {Entry("case", a, b, {DiffMetric::kPsnr, 40.0, 30.0})});
  EXPECT_NE(html.find("<tr class=\"judged\"><th>PSNR</th>"), std::string::npos);
  EXPECT_NE(html.find("judged: WARN below 40, FAIL below 30"), std::string::npos);
  EXPECT_EQ(Count(html, "<tr class=\"judged\">"), 1u);
  for (const char* name : {"values compared", "non-finite mismatches", ">MSE<", ">RMSE<", ">relMSE<", "mean |A",
                           "max |A", "p99 |A", "pixels over 0.001", ">SSIM<", "peak 1 "}) {
    EXPECT_NE(html.find(name), std::string::npos) << name;
  }
}

TEST(HtmlReport, ShowsTheMetadataThatDiffersOrSaysItIsTheSame) {
  ChannelImage a = Constant(4, 4, 1, 1, 1), b = Constant(4, 4, 1, 1, 1);
  a.metadata = {{"seed", "1"}, {"backend", "emulated"}};
  b.metadata = {{"seed", "2"}};
  const std::string differs = RenderHtmlReport("differs", {Entry("case", a, b)});
  EXPECT_NE(differs.find("<tr><th>seed</th><td class=\"\">1</td><td class=\"\">2</td></tr>"), std::string::npos);
  EXPECT_NE(differs.find("<tr><th>backend</th><td class=\"\">emulated</td><td class=\"absent\">(absent)</td></tr>"),
            std::string::npos);
  const std::string same = RenderHtmlReport("same", {Entry("case", a, a)});
  EXPECT_NE(same.find("class=\"same\">the same\n(2 keys)"), std::string::npos);
}

TEST(HtmlReport, ExtraResultsBecomeAKeyValueTable) {
  const ChannelImage a = Constant(4, 4, 1, 1, 1);
  ReportEntry entry = Entry("case", a, a);
  entry.extra = nlohmann::json{{"test", "Welch t"}, {"p_value", 0.25}, {"pixels", {1, 2}}};
  const std::string html = RenderHtmlReport("extra", {entry});
  EXPECT_NE(html.find("<tr><th>test</th><td>Welch t</td></tr>"), std::string::npos);
  EXPECT_NE(html.find("<tr><th>p_value</th><td>0.25</td></tr>"), std::string::npos);
  EXPECT_NE(html.find("<tr><th>pixels</th><td>[1,2]</td></tr>"), std::string::npos);
  EXPECT_EQ(RenderHtmlReport("none", {Entry("case", a, a)}).find("class=\"extra\""), std::string::npos);
}

TEST(ShowImage, SmallImagesAreShownWhole) {
  ChannelImage image = Constant(3, 2, 0.1f, 0.2f, 0.3f);
  const ShownImage shown = ShowImage(image);
  EXPECT_EQ(shown.factor, 1);
  EXPECT_EQ(shown.width, 3);
  EXPECT_EQ(shown.height, 2);
  EXPECT_EQ(shown.rgb, image.values);
  EXPECT_EQ(shown.channels, "R,G,B");
}

TEST(ShowImage, LargeImagesAreBoxFilteredDownWithPartialEdgeBlocks) {
  ChannelImage image;
  image.width = 3;
  image.height = 3;
  image.channels = {"R", "G", "B"};
  for (int p = 0; p < 9; ++p) image.values.insert(image.values.end(), {float(p), 0.0f, 1.0f});
  const ShownImage shown = ShowImage(image, 4);
  ASSERT_EQ(shown.factor, 2);
  ASSERT_EQ(shown.width, 2);
  ASSERT_EQ(shown.height, 2);
  // Pixels 0 1 2 / 3 4 5 / 6 7 8 in 2x2 blocks: {0,1,3,4}, {2,5}, {6,7}, {8}.
  EXPECT_FLOAT_EQ(shown.rgb[0], 2.0f);
  EXPECT_FLOAT_EQ(shown.rgb[3], 3.5f);
  EXPECT_FLOAT_EQ(shown.rgb[6], 6.5f);
  EXPECT_FLOAT_EQ(shown.rgb[9], 8.0f);
  EXPECT_FLOAT_EQ(shown.rgb[2], 1.0f);
}

TEST(ShowImage, TakesRgbByNameIgnoringVarianceOrOneChannelAsGrey) {
  ChannelImage image;
  image.width = image.height = 1;
  image.channels = {"variance.R", "B", "G", "R"};
  image.values = {9.0f, 3.0f, 2.0f, 1.0f};
  const ShownImage rgb = ShowImage(image);
  EXPECT_EQ(rgb.rgb, (std::vector<float>{1.0f, 2.0f, 3.0f}));
  EXPECT_EQ(rgb.channels, "R,G,B");

  image.channels = {"variance.Y", "Y"};
  image.values = {9.0f, 0.5f};
  const ShownImage grey = ShowImage(image);
  EXPECT_EQ(grey.rgb, (std::vector<float>{0.5f, 0.5f, 0.5f}));
  EXPECT_EQ(grey.channels, "Y as grey");
}

TEST(HtmlReport, SaysWhenItShowsAnImageDownsampledAndRepeatsTheHeatmapScale) {
  const ChannelImage a = Constant(1100, 1000, 0.5f, 0.5f, 0.5f), b = Constant(1100, 1000, 0.5f, 0.5f, 0.5f);
  const std::string html = RenderHtmlReport("large", {Entry("case", a, b)});
  EXPECT_NE(html.find("A and B are shown downsampled 2&times; (box filter) to 550&times;500"), std::string::npos);
  EXPECT_NE(html.find("data-width=\"550\" data-height=\"500\""), std::string::npos);
  EXPECT_NE(html.find("<span class=\"legend\">"), std::string::npos) << "the shrunk heatmap's scale as text";
  const ChannelImage small = Constant(64, 64, 0.5f, 0.5f, 0.5f);
  const std::string small_html = RenderHtmlReport("small", {Entry("case", small, small)});
  EXPECT_EQ(small_html.find("downsampled"), std::string::npos);
  EXPECT_EQ(small_html.find("<span class=\"legend\">"), std::string::npos);
}

TEST(WriteHtmlReport, AFailedWriteNamesThePathAndLeavesNothing) {
  const std::filesystem::path dir = std::filesystem::path(testing::TempDir()) / "html_report_write";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir / "report.html" / "occupied");  // a directory holds the name
  const std::string target = (dir / "report.html").string();
  try {
    WriteHtmlReport(target, "<!DOCTYPE html>");
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(target), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(dir / ".report.html.partial.html"));

  const std::string good = (dir / "sub" / "good.html").string();
  WriteHtmlReport(good, "<!DOCTYPE html>");
  std::ifstream in(good);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text, "<!DOCTYPE html>");
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace hpsf
