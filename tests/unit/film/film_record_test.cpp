#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <string>

#include "core/diagnostics.h"
#include "film/film_record.h"
#include "unit/test_dirs.h"

namespace relief::film {
namespace {

// The record of out/orbit.mp4, whose working folder is out/orbit.film.
FilmRecord aRecord(const std::filesystem::path& out) {
    FilmRecord r;
    r.scene = "films/orbit.toml";
    r.sceneSha1 = "A34811D94C15800AA4F48C37E064E9FBCC2E7D74";
    r.fps = 24;
    r.film = out / "orbit.mp4";
    r.sidecar = out / "orbit.json";
    r.framesDir = out / "frames";
    r.filmGiven = true;
    r.terrains = 2;
    r.compileSeconds = 1.25;
    r.limits.maxFilmS = 600;
    r.limits.maxMemoryMB = 900;
    r.limits.locs.keys["limits.max_film_s"] = SourceLoc{"films/orbit.toml", 14, 14};
    r.limits.locs.keys["limits.max_memory_mb"] = SourceLoc{"films/orbit.toml", 0, 0};  // by --set
    for (int k = 1; k <= 3; ++k) {
        FilmFrame f;
        f.settings.number = k;
        f.settings.overrides = {{"camera.azimuth_deg", std::to_string(90 * k)}, {"overlay.subtitle", "\"a \\\"b\\\"\""}};
        f.settings.sunTime = OffsetDateTime{1782000000 + 3600 * k, 720};
        f.sunAltitudeDeg = k == 2 ? -3.5 : 20.0 + k;
        f.night = k == 2;
        f.fileNumber = k == 1 ? 1 : k == 3 ? 2 : 0;
        r.frames.push_back(f);
    }
    return r;
}

void writeText(const std::filesystem::path& file, const std::string& text) {
    std::ofstream(file) << text;
}

std::string readText(const std::filesystem::path& file) {
    std::ifstream in(file);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

TEST(FilmRecord, ReadsBackWhatWasWritten) {
    const auto out = testing::freshTestDir("film-record");
    const auto dir = out / "orbit.film";
    std::filesystem::create_directory(dir);
    const FilmRecord written = aRecord(out);
    writeFilmRecord(written, dir);
    Diagnostics diags;
    const auto read = readFilmRecord(dir, diags);
    ASSERT_TRUE(read) << (diags.all().empty() ? "" : diags.all().front().message);
    EXPECT_EQ(read->scene, written.scene);
    EXPECT_EQ(read->sceneSha1, written.sceneSha1);
    EXPECT_EQ(read->fps, 24);
    EXPECT_EQ(read->film, written.film);
    EXPECT_EQ(read->sidecar, written.sidecar);
    // The frames' folder is not in the record (a folder outside its own): only that they were kept.
    EXPECT_TRUE(read->framesKept);
    EXPECT_TRUE(read->framesDir.empty());
    EXPECT_EQ(readText(dir / "film.json").find((out / "frames").string()), std::string::npos);
    EXPECT_TRUE(read->filmGiven);
    EXPECT_EQ(read->terrains, 2);
    // The limits --resume holds the rest to, and where the scene set them: its errors point there.
    EXPECT_EQ(read->limits.maxFilmS, 600);
    EXPECT_EQ(read->limits.maxMemoryMB, 900);
    const SourceLoc filmLimit = read->limits.locs.at("limits.max_film_s");
    EXPECT_EQ(filmLimit.file, "films/orbit.toml");
    EXPECT_EQ(filmLimit.line, 14);
    EXPECT_EQ(filmLimit.column, 14);
    const SourceLoc memoryLimit = read->limits.locs.at("limits.max_memory_mb");
    EXPECT_EQ(memoryLimit.file, "films/orbit.toml");
    EXPECT_EQ(memoryLimit.line, 0);
    // A limit the scene did not set: the scene file itself.
    FilmRecord unset = written;
    unset.limits = scene::LimitsSpec{};
    writeFilmRecord(unset, dir);
    const auto readUnset = readFilmRecord(dir, diags);
    ASSERT_TRUE(readUnset);
    EXPECT_FALSE(readUnset->limits.locs.has("limits.max_film_s"));
    EXPECT_EQ(readUnset->limits.locs.at("limits.max_film_s").file, "films/orbit.toml");
    ASSERT_EQ(read->frames.size(), 3u);
    for (size_t i = 0; i < 3; ++i) {
        const FilmFrame &a = written.frames[i], &b = read->frames[i];
        EXPECT_EQ(b.settings.number, a.settings.number);
        EXPECT_EQ(b.settings.overrides, a.settings.overrides);
        ASSERT_TRUE(b.settings.sunTime);
        EXPECT_EQ(b.settings.sunTime->utcSeconds, a.settings.sunTime->utcSeconds);
        EXPECT_EQ(b.settings.sunTime->offsetMinutes, 720);
        EXPECT_EQ(b.sunAltitudeDeg, a.sunAltitudeDeg);
        EXPECT_EQ(b.fileNumber, a.fileNumber);
        EXPECT_EQ(b.night, a.night);
    }
    EXPECT_EQ(framePlanName(7), "frame-00007.plan");
}

// A record is an input like any other: a damaged one, one of another film's
// order, or one naming another film, a path or not a video (an output to be
// written over) is refused, naming it.
TEST(FilmRecord, RefusesWhatIsNotAWholeRecord) {
    const auto out = testing::freshTestDir("film-record-bad");
    const auto dir = out / "orbit.film-2";
    std::filesystem::create_directory(dir);
    Diagnostics missing;
    EXPECT_FALSE(readFilmRecord(dir, missing));
    ASSERT_EQ(missing.errorCount(), 1);
    EXPECT_NE(missing.all().front().message.find("not a film's working folder"), std::string::npos);
    EXPECT_EQ(missing.all().front().loc.file, (dir / "film.json").string());

    writeText(dir / "film.json", "{\"relief_film\": 1, \"frames\": [");
    Diagnostics damaged;
    EXPECT_FALSE(readFilmRecord(dir, damaged));
    EXPECT_NE(damaged.all().front().message.find("damaged"), std::string::npos);

    FilmRecord outOfOrder = aRecord(out);
    std::swap(outOfOrder.frames[0].fileNumber, outOfOrder.frames[2].fileNumber);
    writeFilmRecord(outOfOrder, dir);
    Diagnostics order;
    EXPECT_FALSE(readFilmRecord(dir, order));
    EXPECT_NE(order.all().front().message.find("its frames are not a film's"), std::string::npos);

    // It names only its own film, by its file name: never a file elsewhere to be written over.
    FilmRecord otherFilm = aRecord(out);
    otherFilm.film = out / "other.mp4";
    FilmRecord notVideo = aRecord(out);
    notVideo.film = out / "orbit.toml";
    for (const FilmRecord& r : {otherFilm, notVideo}) {
        writeFilmRecord(r, dir);
        Diagnostics foreign;
        EXPECT_FALSE(readFilmRecord(dir, foreign)) << r.film;
        ASSERT_EQ(foreign.errorCount(), 1);
        EXPECT_NE(foreign.all().front().message.find("not this folder's"), std::string::npos);
    }
    writeFilmRecord(aRecord(out), dir);
    const std::string ownText = readText(dir / "film.json");
    for (const char* film : {"../orbit.mp4", "/tmp/orbit.mp4", "x/orbit.mp4"}) {
        std::string text = ownText;
        text.replace(text.find("\"film\": \"orbit.mp4\""), 19, std::string("\"film\": \"") + film + "\"");
        writeText(dir / "film.json", text);
        Diagnostics path;
        EXPECT_FALSE(readFilmRecord(dir, path)) << film;
        ASSERT_EQ(path.errorCount(), 1);
        EXPECT_NE(path.all().front().message.find("not this folder's"), std::string::npos) << film;
    }
    // Limits out of the scene's ranges, or a place that is none.
    FilmRecord negative = aRecord(out), nowhere = aRecord(out);
    negative.limits.maxMemoryMB = -5;
    nowhere.limits.locs.keys["limits.max_film_s"].line = -3;
    for (const FilmRecord& r : {negative, nowhere}) {
        writeFilmRecord(r, dir);
        Diagnostics limits;
        EXPECT_FALSE(readFilmRecord(dir, limits));
        ASSERT_EQ(limits.errorCount(), 1);
        EXPECT_NE(limits.all().front().message.find("damaged"), std::string::npos);
    }
    writeFilmRecord(aRecord(out), dir);
    Diagnostics own;
    EXPECT_TRUE(readFilmRecord(dir, own));
}

// A Linux name is any bytes, JSON holds UTF-8: the film's real name comes back.
TEST(FilmRecord, KeepsANameThatIsNotUtf8) {
    const auto out = testing::freshTestDir("film-record-latin1");
    const std::string name = "caf\xe9";
    const auto dir = out / (name + ".film");
    std::filesystem::create_directory(dir);
    FilmRecord written = aRecord(out);
    written.film = out / (name + ".mp4");
    writeFilmRecord(written, dir);
    Diagnostics diags;
    const auto read = readFilmRecord(dir, diags);
    ASSERT_TRUE(read) << (diags.all().empty() ? "" : diags.all().front().message);
    EXPECT_EQ(read->film, written.film);
    EXPECT_EQ(read->sidecar, out / (name + ".json"));
}

}  // namespace
}  // namespace relief::film
