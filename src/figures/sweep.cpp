#include "figures/sweep.h"

#include <unistd.h>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <fmt/format.h>

#include "core/atomic_file.h"
#include "core/output_set.h"

namespace relief::figures {

namespace fs = std::filesystem;

namespace {
constexpr const char* kFonts[] = {"/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",
                                  "/usr/share/fonts/dejavu/DejaVuSans.ttf"};
std::string findFont() {
    for (const char* f : kFonts)
        if (fs::exists(f)) return f;
    return "";
}
}  // namespace

std::vector<std::vector<std::pair<std::string, std::string>>> combinations(
    const std::vector<Variation>& variations) {
    std::vector<std::vector<std::pair<std::string, std::string>>> out;
    std::vector<size_t> index(variations.size(), 0);  // an odometer, first digit fastest
    for (const auto& v : variations)
        if (v.values.empty()) return out;
    while (true) {
        std::vector<std::pair<std::string, std::string>> combo;
        for (size_t k = 0; k < variations.size(); ++k)
            combo.emplace_back(variations[k].key, variations[k].values[index[k]]);
        out.push_back(std::move(combo));
        size_t k = 0;
        while (k < variations.size() && ++index[k] == variations[k].values.size()) index[k++] = 0;
        if (k == variations.size()) break;
    }
    return out;
}

std::string writeContactSheet(const std::vector<Tile>& tiles, int columns, const std::string& title,
                              const fs::path& out) {
    if (tiles.empty()) return "no stills to assemble";
    std::vector<OIIO::ImageBuf> images;
    int tileW = 0, tileH = 0;
    for (const auto& t : tiles) {
        OIIO::ImageBuf b(t.image.string());
        if (!b.read(0, 0, true, OIIO::TypeDesc::FLOAT)) return fmt::format("cannot read {}", t.image.string());
        tileW = std::max(tileW, b.spec().width);
        tileH = std::max(tileH, b.spec().height);
        images.push_back(std::move(b));
    }
    const int cols = columns > 0 ? columns : static_cast<int>(tiles.size());
    const int rows = (static_cast<int>(tiles.size()) + cols - 1) / cols;
    const int pad = 12, labelH = 46, titleH = title.empty() ? 0 : 44;
    const int W = cols * tileW + (cols + 1) * pad;
    const int H = titleH + rows * (tileH + labelH) + (rows + 1) * pad;
    OIIO::ImageBuf sheet(OIIO::ImageSpec(W, H, 3, OIIO::TypeDesc::FLOAT));
    const float white[3] = {1, 1, 1}, black[3] = {0.1f, 0.1f, 0.1f};
    OIIO::ImageBufAlgo::fill(sheet, white);
    const std::string font = findFont();
    if (!title.empty() && !font.empty())
        OIIO::ImageBufAlgo::render_text(sheet, pad, pad + 26, title, 22, font, black);
    for (size_t i = 0; i < images.size(); ++i) {
        const int c = static_cast<int>(i) % cols, r = static_cast<int>(i) / cols;
        const int x = pad + c * (tileW + pad), y = titleH + pad + r * (tileH + labelH + pad);
        OIIO::ImageBuf rgb = OIIO::ImageBufAlgo::channels(images[i], 3, {0, 1, 2});
        OIIO::ImageBufAlgo::paste(sheet, x, y, 0, 0, rgb);
        if (!font.empty()) {
            // Drawn into a label strip of the tile's width, so long text is
            // clipped there instead of running into the next tile.
            OIIO::ImageBuf strip(OIIO::ImageSpec(tileW, labelH, 3, OIIO::TypeDesc::FLOAT));
            OIIO::ImageBufAlgo::fill(strip, white);
            // OIIO 2.4's render_text takes bytes, not UTF-8: spell o-umlaut plainly.
            std::string label;
            for (size_t k = 0; k < tiles[i].label.size(); ++k) {
                if (tiles[i].label.compare(k, 2, "\xc3\xb6") == 0) {
                    label.push_back('o');
                    ++k;
                } else {
                    label.push_back(tiles[i].label[k]);
                }
            }
            OIIO::ImageBufAlgo::render_text(strip, 2, 18, label, 15, font, black);
            OIIO::ImageBufAlgo::paste(sheet, x, y + tileH, 0, 0, strip);
        }
    }
    try {
        writeThroughTemporary(out, [&](const fs::path& temp) {
            return sheet.write(temp.string(), OIIO::TypeDesc::UINT8) ? std::string() : sheet.geterror();
        });
    } catch (const OutputError& e) {
        return e.what();
    }
    return font.empty() ? "warning: no DejaVu Sans font (apt-get install fonts-dejavu-core): labels left out" : "";
}

}  // namespace relief::figures

namespace relief::figures {

namespace {

std::string labelOf(const std::vector<std::pair<std::string, std::string>>& combo) {
    std::string label;
    for (const auto& [k, v] : combo) label += fmt::format("{}{} = {}", label.empty() ? "" : ", ", k.substr(k.find('.') + 1), v);
    return label;
}

SceneJob jobOf(const SweepRequest& request, const std::vector<std::pair<std::string, std::string>>& combo,
               const fs::path& output) {
    SceneJob job;
    job.scenePath = request.scenePath;
    job.overrides = request.base;
    job.overrides.insert(job.overrides.end(), combo.begin(), combo.end());
    job.output = output;
    job.templatesDir = request.templatesDir;
    job.threads = request.threads;
    job.tiles = request.tiles;
    return job;
}

// One sweep between its phases: its combinations, their plans and its one set
// of outputs. Each phase returns false when the sweep stops there (the failure
// reported with its Finished event); the plans go with the run.
class SweepRun {
public:
    SweepRun(const SweepRequest& request, const std::function<void(const SweepEvent&)>& onEvent)
        : request_(request), onEvent_(onEvent), combos_(combinations(request.variations)),
          stills_(request.sheet.parent_path() / (request.sheet.stem().string() + "-stills")) {}
    SweepRun(const SweepRun&) = delete;
    ~SweepRun() {
        std::error_code ec;
        for (auto& p : planned_)
            if (p.plan) fs::remove_all(p.plan->dir, ec);
    }

    // Every combination read and checked before any is rendered: a bad value
    // anywhere stops the sweep with nothing written.
    bool checkAll(SweepResult& result) {
        for (size_t i = 0; i < combos_.size(); ++i) {
            Diagnostics diags;
            if (loadScene(request_.scenePath, diags, jobOf(request_, combos_[i], {}).overrides)) continue;
            const JobOutcome refused;
            return reportStop(i + 1, labelOf(combos_[i]), refused, diags, JobStatus::BadInput, result);
        }
        return true;
    }

    bool planAll(SweepResult& result) {
        for (size_t i = 0; i < combos_.size(); ++i) {
            SceneJob job = jobOf(request_, combos_[i], stills_ / fmt::format("{:03}.png", i + 1));
            job.outputs = &outputs_;
            emit({SweepEvent::Kind::Started, i + 1, combos_.size(), labelOf(combos_[i])});
            Diagnostics diags;
            planned_.push_back(planJob(job, diags, {}));
            const JobOutcome& outcome = planned_.back().outcome;
            if (outcome.status != JobStatus::Ok)
                return reportStop(i + 1, labelOf(combos_[i]), outcome, diags, outcome.status, result);
        }
        return true;
    }

    // All the plans' tiles at once, here or on Slurm.
    bool renderAll(SweepResult& result) {
        std::vector<const plan::RenderPlan*> plans;
        for (const auto& p : planned_) plans.push_back(&*p.plan);
        execute::Options e = request_.execution;
        // Slurm's job folder (script, task list, logs) beside the sheet: kept when a task fails,
        // since the message names its log, and removed once every still is rendered.
        const bool ownJobDir = e.jobDir.empty();
        if (ownJobDir) e.jobDir = request_.sheet.parent_path() / (request_.sheet.stem().string() + ".slurm");
        const auto told = [&](const ProgressEvent& line) {
            SweepEvent event{SweepEvent::Kind::Rendering, 0, plans.size(), "renders"};
            event.render = &line;
            emit(event);
        };
        Diagnostics diags;
        const PlansRendered rendered = renderPlans(plans, e, {told, "stills", 0, 0, {}}, diags);
        if (rendered.status != JobStatus::Ok) {
            JobOutcome failed;
            failed.status = rendered.status;
            failed.render.error = rendered.error;
            return reportStop(0, "renders", failed, diags, failed.status, result);
        }
        std::error_code ec;
        if (ownJobDir) fs::remove_all(e.jobDir, ec);
        return true;
    }

    bool finishAll(SweepResult& result) {
        for (size_t i = 0; i < planned_.size(); ++i) {
            PlannedJob& p = planned_[i];
            Diagnostics diags;
            if (!finishPlan(*p.plan, outputs_, false, false, true, p.outcome, diags))
                p.outcome.status = JobStatus::BadInput;
            if (p.outcome.status != JobStatus::Ok)
                return reportStop(i + 1, labelOf(combos_[i]), p.outcome, diags, p.outcome.status, result);
            SweepEvent event{SweepEvent::Kind::Finished, i + 1, combos_.size(), labelOf(combos_[i])};
            event.outcome = &p.outcome;
            event.diags = &diags;
            emit(event);
            result.tiles.push_back(
                {p.outcome.paths.still, fmt::format("{}\n{}", labelOf(combos_[i]), p.outcome.compiled->surface.certified)});
        }
        return true;
    }

    // The sheet beside the stills; the set committed only when it is written.
    void writeSheet(SweepResult& result) {
        const int columns = request_.columns > 0         ? request_.columns
                            : request_.variations.empty() ? 1
                                                          : static_cast<int>(request_.variations[0].values.size());
        std::vector<Tile> staged = result.tiles;
        for (auto& t : staged) t.image = outputs_.staged(t.image);
        try {
            result.sheetMessage = writeContactSheet(staged, columns, request_.scenePath.filename().string(),
                                                    outputs_.add(request_.sheet, "the contact sheet", true));
            result.sheetWritten = result.sheetMessage.empty() || result.sheetMessage.rfind("warning", 0) == 0;
            if (result.sheetWritten) outputs_.commit();
        } catch (const std::runtime_error& e) {
            result.sheetMessage = e.what();
            result.sheetWritten = false;
        }
    }

private:
    void emit(const SweepEvent& e) const {
        if (onEvent_) onEvent_(e);
    }
    bool reportStop(size_t index, const std::string& label, const JobOutcome& outcome, const Diagnostics& diags,
                 JobStatus status, SweepResult& result) const {
        SweepEvent event{SweepEvent::Kind::Finished, index, combos_.size(), label};
        event.outcome = &outcome;
        event.diags = &diags;
        emit(event);
        result.status = status;
        return false;
    }

    const SweepRequest& request_;
    const std::function<void(const SweepEvent&)>& onEvent_;
    const std::vector<std::vector<std::pair<std::string, std::string>>> combos_;
    const fs::path stills_;
    OutputSet outputs_;  // declared before the plans: they are removed first
    std::vector<PlannedJob> planned_;
};

}  // namespace

SweepResult runSweep(const SweepRequest& request, const std::function<void(const SweepEvent&)>& onEvent) {
    SweepResult result;
    SweepRun run(request, onEvent);
    if (run.checkAll(result) && run.planAll(result) && run.renderAll(result) && run.finishAll(result))
        run.writeSheet(result);
    return result;
}

}  // namespace relief::figures
