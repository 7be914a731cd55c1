// GDAL for untrusted scenes: no file the scene does not name, no network;
// frames across the antimeridian; nets held to the memory budget.
#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <sys/stat.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <fstream>
#include <thread>

#include <cpl_conv.h>
#include <cpl_http.h>
#include <cpl_vsi.h>
#include <fmt/format.h>
#include <gdal.h>
#include <ogr_srs_api.h>

#include "geo/gdal_crs.h"
#include "geo/gdal_setup.h"
#include "geo/normalize.h"
#include "geo/raster.h"
#include "core/text_escape.h"
#include "unit/test_dirs.h"

namespace relief::geo {
namespace {

namespace fs = std::filesystem;
using relief::testing::freshTestDir;

// A TCP listener on a loopback port that counts the connections made to it.
class Listener {
public:
    Listener() {
        fd_ = ::socket(AF_INET, SOCK_STREAM, 0);
        sockaddr_in a{};
        a.sin_family = AF_INET;
        a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
        socklen_t len = sizeof a;
        if (::bind(fd_, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0 || ::listen(fd_, 16) != 0 ||
            ::getsockname(fd_, reinterpret_cast<sockaddr*>(&a), &len) != 0)
            throw std::runtime_error("no loopback listener");
        port_ = ntohs(a.sin_port);
        thread_ = std::thread([this] {
            while (!stop_) {
                pollfd p{fd_, POLLIN, 0};
                if (::poll(&p, 1, 50) > 0) {
                    const int c = ::accept(fd_, nullptr, nullptr);
                    if (c >= 0) ++connections_, ::close(c);
                }
            }
        });
    }
    ~Listener() {
        stop_ = true;
        thread_.join();
        ::close(fd_);
    }
    int port() const { return port_; }
    int connections() const { return connections_; }

private:
    int fd_ = -1, port_ = 0;
    std::atomic<bool> stop_{false};
    std::atomic<int> connections_{0};
    std::thread thread_;
};

void write(const fs::path& p, const std::string& text) { std::ofstream(p) << text; }

// A VRT of one band whose one source (or raw file) is `source`.
std::string vrtWith(const std::string& band) {
    return "<VRTDataset rasterXSize=\"4\" rasterYSize=\"4\"><SRS>EPSG:2193</SRS>"
           "<GeoTransform>1757000, 10, 0, 5917000, 0, -10</GeoTransform>" +
           band + "</VRTDataset>";
}
std::string simpleSource(const std::string& file, bool relative) {
    return fmt::format("<VRTRasterBand dataType=\"Float32\" band=\"1\"><SimpleSource><SourceFilename "
                       "relativeToVRT=\"{}\">{}</SourceFilename><SourceBand>1</SourceBand></SimpleSource>"
                       "</VRTRasterBand>",
                       relative ? 1 : 0, file);
}

fs::path writeTiff(const fs::path& path, const char* srs, double x0, double dx, double y0, double dy, int cols,
                   int rows, const std::function<float(double, double)>& height) {
    setUpGdal();
    GDALDatasetH ds = GDALCreate(GDALGetDriverByName("GTiff"), path.c_str(), cols, rows, 1, GDT_Float32, nullptr);
    double geo[6] = {x0, dx, 0, y0, 0, dy};
    GDALSetGeoTransform(ds, geo);
    OGRSpatialReferenceH s = OSRNewSpatialReference(nullptr);
    OSRSetFromUserInput(s, srs);
    char* wkt = nullptr;
    OSRExportToWkt(s, &wkt);
    GDALSetProjection(ds, wkt);
    CPLFree(wkt);
    OSRDestroySpatialReference(s);
    std::vector<float> cells(static_cast<size_t>(cols) * rows);
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c) cells[size_t(r) * cols + c] = height(x0 + (c + 0.5) * dx, y0 + (r + 0.5) * dy);
    EXPECT_EQ(GDALRasterIO(GDALGetRasterBand(ds, 1), GF_Write, 0, 0, cols, rows, cells.data(), cols, rows,
                           GDT_Float32, 0, 0),
              CE_None);
    GDALSetRasterUnitType(GDALGetRasterBand(ds, 1), "m");
    GDALClose(ds);
    return path;
}

// GDAL's network paths and web drivers, asked for directly or through a VRT
// or a CRS, make no connection: a listener on loopback, set as GDAL's HTTP
// proxy (so that relief's dead proxy is not what stops them), counts none;
// GDAL's own HTTP call through the same proxy reaches it (the test can see a
// connection).
TEST(UntrustedGdal, ReachesNoNetwork) {
    setUpGdal();
    EXPECT_STREQ(CPLGetConfigOption("GDAL_HTTP_PROXY", ""), "127.0.0.1:9");
    EXPECT_FALSE(OSRGetPROJEnableNetwork());
    Listener server;
    const std::string proxy = fmt::format("127.0.0.1:{}", server.port());
    const std::string url = fmt::format("http://127.0.0.1:{}/dem.tif", server.port());
    CPLSetConfigOption("GDAL_HTTP_PROXY", proxy.c_str());
    CPLSetConfigOption("AWS_S3_ENDPOINT", proxy.c_str());
    CPLSetConfigOption("AWS_HTTPS", "NO");
    for (const std::string& name :
         {"/vsicurl/" + url, url, "/vsicurl_streaming/" + url, std::string("/vsis3/b/dem.tif"),
          std::string("/vsis3_streaming/b/dem.tif"), std::string("/vsigs/b/dem.tif"), "WMS:" + url,
          "/vsizip//vsicurl/" + url + "/x.tif"}) {
        CPLPushErrorHandler(CPLQuietErrorHandler);
        GDALDatasetH ds = GDALOpenEx(name.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, nullptr, nullptr, nullptr);
        VSIStatBufL st;
        const int found = VSIStatL(name.c_str(), &st);
        CPLPopErrorHandler();
        EXPECT_EQ(ds, nullptr) << name;
        EXPECT_NE(found, 0) << name;
        if (ds) GDALClose(ds);
    }
    // A VRT with a network source, opened by GDAL itself (relief refuses it first, below).
    const fs::path dir = freshTestDir("no-network");
    write(dir / "net.vrt", vrtWith(simpleSource("/vsicurl/" + url, false)));
    CPLPushErrorHandler(CPLQuietErrorHandler);
    GDALDatasetH vrt = GDALOpen((dir / "net.vrt").c_str(), GA_ReadOnly);
    float cell = 0;
    if (vrt && GDALRasterIO(GDALGetRasterBand(vrt, 1), GF_Read, 0, 0, 1, 1, &cell, 1, 1, GDT_Float32, 0, 0) == CE_None)
        ADD_FAILURE() << "a network source was read";
    CPLPopErrorHandler();
    if (vrt) GDALClose(vrt);
    EXPECT_EQ(gdalInputProblem(dir / "net.vrt"),
              "it is a VRT, and it holds the source \"/vsicurl/" + url +
                  "\", which is not a plain file name (no virtual, network or driver paths)");
    OGRSpatialReferenceH srs = OSRNewSpatialReference(nullptr);
    std::string problem;
    EXPECT_FALSE(crsFromText(srs, "http://127.0.0.1:" + std::to_string(server.port()) + "/crs", problem));
    EXPECT_EQ(problem, "holds \"://\", which would make relief read a file or the network; give an EPSG code or WKT");
    EXPECT_TRUE(crsFromText(srs, "EPSG:2193", problem));
    OSRDestroySpatialReference(srs);
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    EXPECT_EQ(server.connections(), 0);
    // The control: GDAL's HTTP call through the same proxy does arrive.
    CPLPushErrorHandler(CPLQuietErrorHandler);
    CPLHTTPDestroyResult(CPLHTTPFetch(url.c_str(), nullptr));
    CPLPopErrorHandler();
    for (int i = 0; i < 40 && server.connections() == 0; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(50));
    EXPECT_GT(server.connections(), 0) << "the listener saw no connection even from GDAL's own HTTP call";
    CPLSetConfigOption("GDAL_HTTP_PROXY", "127.0.0.1:9");
    CPLSetConfigOption("AWS_S3_ENDPOINT", nullptr);
    CPLSetConfigOption("AWS_HTTPS", nullptr);
}

// A VRT reads only plain files in its own folder: each way it could name
// another file, or read raw bytes, or run code, is refused with its reason.
TEST(UntrustedGdal, VrtsNameOnlyFilesBesideThem) {
    const fs::path dir = freshTestDir("vrt");
    fs::create_directories(dir / "tiles" / "sub");
    writeTiff(dir / "tiles" / "a.tif", "EPSG:2193", 1757000, 10, 5917000, -10, 4, 4, [](double, double) { return 7.f; });
    writeTiff(dir / "secret.tif", "EPSG:2193", 1757000, 10, 5917000, -10, 4, 4, [](double, double) { return 1.f; });
    write(dir / "secret.txt", "root:$6$salt$hash:19000:0:99999:7:::\n");
    fs::create_symlink(dir / "secret.tif", dir / "tiles" / "link.tif");
    const auto problem = [&](const std::string& name, const std::string& xml) {
        write(dir / "tiles" / name, xml);
        return gdalInputProblem(dir / "tiles" / name);
    };
    const std::string plain = "it is a VRT, and it holds ";
    EXPECT_EQ(problem("ok.vrt", vrtWith(simpleSource("a.tif", true))), "");
    EXPECT_EQ(problem("sub-ok.vrt", vrtWith(simpleSource("sub/../a.tif", true))), "");
    EXPECT_EQ(problem("up.vrt", vrtWith(simpleSource("../secret.tif", true))),
              plain + "the source \"../secret.tif\", a file outside the VRT's folder");
    EXPECT_EQ(problem("abs.vrt", vrtWith(simpleSource((dir / "secret.tif").string(), false))),
              plain + "the source \"" + (dir / "secret.tif").string() + "\", a file outside the VRT's folder");
    EXPECT_EQ(problem("link.vrt", vrtWith(simpleSource("link.tif", true))),
              plain + "the source \"link.tif\", a file outside the VRT's folder");
    EXPECT_EQ(problem("raw.vrt",
                      vrtWith("<VRTRasterBand dataType=\"Byte\" band=\"1\" subClass=\"VRTRawRasterBand\">"
                              "<SourceFilename relativeToVRT=\"1\">a.tif</SourceFilename></VRTRasterBand>")),
              plain + "a VRTRawRasterBand, which reads the raw bytes of any file");
    EXPECT_EQ(problem("subfile.vrt", vrtWith(simpleSource("/vsisubfile/0_100," + (dir / "secret.txt").string(), false))),
              plain + "the source \"" + printableExcerpt("/vsisubfile/0_100," + (dir / "secret.txt").string(), 80) +
                  "\", which is not a plain file name (no virtual, network or driver paths)");
    EXPECT_EQ(problem("mem.vrt", vrtWith(simpleSource("MEM:::DATAPOINTER=0x10,PIXELS=4,LINES=4", false))),
              plain + "the source \"MEM:::DATAPOINTER=0x10,PIXELS=4,LINES=4\", which is not a plain file name (no "
                      "virtual, network or driver paths)");
    EXPECT_EQ(problem("derived.vrt", vrtWith("<VRTRasterBand dataType=\"Float32\" band=\"1\" "
                                             "subClass=\"VRTDerivedRasterBand\"><PixelFunctionType>sum"
                                             "</PixelFunctionType></VRTRasterBand>")),
              plain + "a VRTDerivedRasterBand (relief reads bands of sources only)");
    EXPECT_EQ(problem("warped.vrt", "<VRTDataset subClass=\"VRTWarpedDataset\" rasterXSize=\"4\" rasterYSize=\"4\">"
                                    "<GDALWarpOptions><SourceDataset>a.tif</SourceDataset></GDALWarpOptions>"
                                    "</VRTDataset>"),
              plain + "a VRTWarpedDataset (relief reads plain VRTs of sources only)");
    EXPECT_EQ(problem("init.vrt", "<VRTDataset rasterXSize=\"4\" rasterYSize=\"4\"><SRS>+init=" +
                                      (dir / "secret.txt").string() + ":1</SRS>" + simpleSource("a.tif", true) +
                                      "</VRTDataset>"),
              plain + "an SRS with +init, which makes PROJ read a file");
    // Nested: a VRT beside it that reads raw bytes is refused through the first.
    write(dir / "tiles" / "inner.vrt",
          vrtWith("<VRTRasterBand dataType=\"Byte\" band=\"1\" subClass=\"VRTRawRasterBand\">"
                  "<SourceFilename relativeToVRT=\"1\">a.tif</SourceFilename></VRTRasterBand>"));
    EXPECT_EQ(problem("outer.vrt", vrtWith(simpleSource("inner.vrt", true))),
              plain + "the source \"inner.vrt\", a VRT: it holds a VRTRawRasterBand, which reads the raw bytes of any "
                      "file");
    // GDAL reads element names in any case: so does relief.
    EXPECT_EQ(problem("lower.vrt", "<vrtdataset rasterXSize=\"4\" rasterYSize=\"4\"><vrtrasterband dataType=\"Byte\" "
                                   "band=\"1\" subclass=\"vrtrawrasterband\"><sourcefilename>" +
                                       (dir / "secret.txt").string() + "</sourcefilename></vrtrasterband></vrtdataset>"),
              plain + "a VRTRawRasterBand, which reads the raw bytes of any file");
    EXPECT_EQ(problem("lower-source.vrt", vrtWith("<VRTRasterBand dataType=\"Float32\" band=\"1\"><simplesource>"
                                                  "<SOURCEFILENAME>../secret.tif</SOURCEFILENAME></simplesource>"
                                                  "</VRTRasterBand>")),
              plain + "the source \"../secret.tif\", a file outside the VRT's folder");
    // Elements that name other datasets, or move where sources resolve, are not a plain VRT's.
    EXPECT_EQ(problem("overview.vrt", vrtWith("<VRTRasterBand dataType=\"Float32\" band=\"1\"><Overview>"
                                              "<SourceFilename relativeToVRT=\"1\">a.tif</SourceFilename></Overview>"
                                              "</VRTRasterBand>")),
              plain + "a <Overview> element, which relief does not read in a scene's VRT");
    EXPECT_EQ(problem("ovmeta.vrt", "<VRTDataset rasterXSize=\"4\" rasterYSize=\"4\"><Metadata domain=\"OVERVIEWS\">"
                                    "<MDI key=\"OVERVIEW_FILE\">../secret.tif</MDI></Metadata></VRTDataset>"),
              plain + "overviews in another file (metadata domain OVERVIEWS)");
    EXPECT_EQ(problem("ovmdi.vrt", "<VRTDataset rasterXSize=\"4\" rasterYSize=\"4\"><Metadata>"
                                   "<MDI key=\"overview_file\">../secret.tif</MDI></Metadata></VRTDataset>"),
              plain + "an OVERVIEW_FILE, which names another dataset");
    EXPECT_EQ(problem("options.vrt", vrtWith("<VRTRasterBand dataType=\"Float32\" band=\"1\"><SimpleSource>"
                                             "<SourceFilename relativeToVRT=\"1\">a.tif</SourceFilename><OpenOptions>"
                                             "<OOI key=\"ROOT_PATH\">/etc</OOI></OpenOptions></SimpleSource>"
                                             "</VRTRasterBand>")),
              plain + "a <OpenOptions> element, which relief does not read in a scene's VRT");
    EXPECT_EQ(problem("atoi.vrt", vrtWith("<VRTRasterBand dataType=\"Float32\" band=\"1\"><SimpleSource><SourceFilename "
                                          "relativeToVRT=\"01\">a.tif</SourceFilename></SimpleSource></VRTRasterBand>")),
              plain + "the source \"a.tif\" with relativeToVRT=\"01\" (write 0 or 1)");
    EXPECT_EQ(problem("split.vrt", vrtWith("<VRTRasterBand dataType=\"Float32\" band=\"1\"><SimpleSource><SourceFilename "
                                           "relativeToVRT=\"1\">a.tif<!-- x -->../secret.tif</SourceFilename>"
                                           "</SimpleSource></VRTRasterBand>")),
              plain + "a source whose file name is not one plain text");
    // A VRT that names itself, however deep, ends.
    EXPECT_EQ(problem("self.vrt", vrtWith(simpleSource("self.vrt", true) + simpleSource("self.vrt", true))),
              plain + "the source \"self.vrt\", a VRT that leads back to itself");
    // The good one reads the tile's heights.
    scene::SamplesSpec spec;
    spec.path = dir / "tiles" / "ok.vrt";
    spec.pathAsWritten = "ok.vrt";
    spec.verticalUnit = "m";
    Diagnostics diags;
    scene::NetSpec half;  // 4 x 4 cells of 10 m: their centres hold 3 x 3 nodes at 10 m, too few
    half.spacingM = 5;
    const auto net = rasterNet(spec, {}, half, diags);
    ASSERT_TRUE(net) << (diags.all().empty() ? "" : formatDiagnostic(diags.all()[0]));
    EXPECT_NEAR(net->grid.points[net->grid.points.size() / 2].z, 7.0, 1e-6);
}

// GDAL reads files beside a raster by its name: each is checked as the raster
// is, whether the folder is listed for the raster or once for many (tiles).
TEST(UntrustedGdal, FilesBesideARasterAreCheckedToo) {
    const fs::path dir = freshTestDir("sidecars");
    const fs::path dem = writeTiff(dir / "dem.tif", "EPSG:2193", 1757000, 10, 5917000, -10, 4, 4,
                                   [](double, double) { return 5.f; });
    auto problems = [&] {
        const FolderNames names(dir);
        const std::string listed = gdalInputProblem(dem, &names), alone = gdalInputProblem(dem);
        EXPECT_EQ(listed, alone);
        return alone;
    };
    EXPECT_EQ(problems(), "");
    const std::string fix = "; remove it, or put the real file there";
    ASSERT_EQ(::mkfifo((dir / "dem.tif.ovr").c_str(), 0600), 0);
    EXPECT_EQ(problems(),
              "the file beside it that GDAL would read with it, dem.tif.ovr, is not a plain "
              "file (it is a FIFO (a named pipe), not a file)" + fix);
    fs::remove(dir / "dem.tif.ovr");
    write(dir / "dem.tif.ovr", vrtWith("<VRTRasterBand dataType=\"Byte\" band=\"1\" subClass=\"VRTRawRasterBand\">"
                                      "<SourceFilename>/etc/passwd</SourceFilename></VRTRasterBand>"));
    EXPECT_EQ(problems(),
              "the file beside it that GDAL would read with it, dem.tif.ovr, is a VRT, and it "
              "holds a VRTRawRasterBand, which reads the raw bytes of any file");
    fs::remove(dir / "dem.tif.ovr");
    fs::create_symlink("/dev/zero", dir / "dem.prj");
    EXPECT_EQ(problems(),
              "the file beside it that GDAL would read with it, dem.prj, is not a plain file "
              "(it is a device, not a file)" + fix);
    fs::remove(dir / "dem.prj");
    // The side files GDAL reads whole are held to kMaxSideTextBytes (sparse: no disk is written);
    // those it reads a piece at a time are not.
    for (const char* whole : {"dem.prj", "dem.tfw", "dem.tifw", "dem.wld", "dem.tif.aux.xml", "dem.hdr"}) {
        write(dir / whole, "");
        fs::resize_file(dir / whole, kMaxSideTextBytes + 1);
        EXPECT_EQ(problems(), fmt::format("the file beside it that GDAL would read whole with it, {}: it is 16 MB, "
                                          "more than the 16 MB such a file may be{}",
                                          whole, fix));
        fs::resize_file(dir / whole, kMaxSideTextBytes);
        EXPECT_EQ(problems(), "") << whole;
        fs::remove(dir / whole);
    }
    write(dir / "dem.tif.ovr", "");
    fs::resize_file(dir / "dem.tif.ovr", 4 * kMaxSideTextBytes);
    EXPECT_EQ(problems(), "");
    fs::remove(dir / "dem.tif.ovr");
    // GDAL looks for side files in any case (DEM.TIF.OVR for dem.tif): so does the check.
    fs::create_symlink("/dev/zero", dir / "DEM.TIF.OVR");
    EXPECT_EQ(problems(),
              "the file beside it that GDAL would read with it, DEM.TIF.OVR, is not a plain file "
              "(it is a device, not a file)" + fix);
    EXPECT_EQ(FolderNames(dir).beside("dem.tif"), (std::vector<std::string>{"dem.tif", "DEM.TIF.OVR"}));
}

TEST(Frames, TheCentreOfLongitudesIsOnTheCircle) {
    EXPECT_DOUBLE_EQ(std::fabs(centreLongitude({179, -179})), 180);
    EXPECT_DOUBLE_EQ(centreLongitude({179.5, -179.5, 179.9}), 180);
    EXPECT_DOUBLE_EQ(centreLongitude({-10, 10}), 0);
    EXPECT_DOUBLE_EQ(centreLongitude({170, 175, -175}), 177.5);
    EXPECT_NEAR(centreLongitude({-3.2, -3.1}), -3.15, 1e-12);
    EXPECT_DOUBLE_EQ(centreLongitude({42}), 42);
}

// Samples and a raster on both sides of the antimeridian (Taveuni, Fiji, at
// lon 180): the frame is centred there, the net spans the data's 2 km and not
// the Earth, no sample is refused and no node of the raster is masked.
TEST(Frames, DataAcrossTheAntimeridian) {
    std::vector<GeoSample> samples;
    for (int i = 0; i < 9; ++i)
        for (int j = 0; j < 9; ++j) {
            const double lon = std::remainder(179.99 + 0.0025 * i, 360.0), lat = -16.8 + 0.0025 * j;
            samples.push_back({lon, lat, 100.0 + i + j, {}});
        }
    const fs::path dir = freshTestDir("antimeridian");
    const auto raster = writeTiff(dir / "taveuni.tif", "EPSG:4326", 179.98, 0.001, -16.78, -0.001, 40, 20,
                                  [](double lon, double) { return float(100 + 1000 * (lon - 179.98)); });
    for (auto kind : {scene::FrameKind::Utm, scene::FrameKind::Local}) {
        scene::FrameSpec frame;
        frame.kind = kind;
        Diagnostics diags;
        const auto net = normalize(frame, {}, "samples.csv", samples, diags);
        ASSERT_TRUE(net) << (diags.all().empty() ? "" : formatDiagnostic(diags.all()[0]));
        EXPECT_LT(net->xMax() - net->x0, 3000) << net->frame.describe();
        EXPECT_LT(net->yMax() - net->y0, 3000);
        EXPECT_EQ(net->sampleCount, samples.size());
        scene::SamplesSpec spec;
        spec.path = raster;
        spec.pathAsWritten = "taveuni.tif";
        spec.nodata = scene::NodataPolicy::Mask;
        const auto fromRaster = rasterNet(spec, frame, {}, diags);
        ASSERT_TRUE(fromRaster) << (diags.all().empty() ? "" : formatDiagnostic(diags.all()[0]));
        EXPECT_EQ(fromRaster->maskedCount(), 0u) << fromRaster->frame.describe();
        EXPECT_LT(fromRaster->xMax() - fromRaster->x0, 5000);
        // East of the line the heights go on rising: lon 180.01 (written -179.99) is 130 m.
        const auto p = forward(fromRaster->frame, {-179.99, -16.79, 0});
        ASSERT_TRUE(p);
        EXPECT_NEAR(fromRaster->sample(p->x, p->y).value_or(-1), 130, 0.6) << fromRaster->frame.describe();
    }
}

// Nets are held to the memory budget from their size, before anything is allocated.
TEST(NetBudget, RefusesANetTooLargeBeforeMakingIt) {
    Frame frame;
    frame.kind = scene::FrameKind::Local;
    GeoGrid net;
    net.frame = frame;
    scene::NetSpec spec;
    spec.rows = spec.cols = 100000;
    spec.locs.keys["net.rows"] = {"scene.toml", 3, 8};
    NetBudget budget;
    budget.maxNodes = 1e6;
    budget.why = "limits.max_memory_mb = 48 (48 bytes a node)";
    Diagnostics diags;
    EXPECT_FALSE(layoutNet(spec, {0, 0, 1000, 1000}, 0, net, diags, budget));
    EXPECT_EQ(formatDiagnostic(diags.all().at(0)),
              "scene.toml:3:8: error: net.rows = 100000 and net.cols = 100000 give 1e+10 nodes, more than 1e+06 "
              "allowed by limits.max_memory_mb = 48 (48 bytes a node): use fewer rows and columns");
    // The data's own spacing, when it is too fine, is not blamed on a key the scene never set.
    Diagnostics fine;
    EXPECT_FALSE(layoutNet({}, {0, 0, 100000, 100000}, 0.01, net, fine, budget));
    EXPECT_EQ(formatDiagnostic(fine.all().at(0)).find("net.spacing_m ="), std::string::npos);
    EXPECT_NE(formatDiagnostic(fine.all().at(0)).find("a net at the data's own spacing, 0.01 m, gives"),
              std::string::npos)
        << formatDiagnostic(fine.all().at(0));
}

}  // namespace
}  // namespace relief::geo
