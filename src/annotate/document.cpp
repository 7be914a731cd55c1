#include "annotate/overlay.h"

#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <cairo-pdf.h>
#include <cairo-svg.h>

#include "annotate/paint.h"
#include "core/output_set.h"
#include "core/text_escape.h"

namespace relief::annotate {

namespace {

// An invisible text of every string drawn, over its glyphs: cairo's SVG draws
// glyphs as outlines, which a reader cannot search or copy. Escaped as text.
std::string svgTextLayer(const std::vector<DrawnText>& texts, double pointsPerPixel) {
    std::string layer = "<g id=\"relief-text\" fill-opacity=\"0\" font-family=\"DejaVu Sans\">\n";
    for (const auto& t : texts)
        layer += fmt::format("<text x=\"{:.2f}\" y=\"{:.2f}\" font-size=\"{:.2f}\"{} textLength=\"{:.2f}\" "
                             "lengthAdjust=\"spacingAndGlyphs\">{}</text>\n",
                             t.x * pointsPerPixel, (t.y + 0.8 * t.h) * pointsPerPixel, t.sizePx * pointsPerPixel,
                             t.bold ? " font-weight=\"bold\"" : "", t.w * pointsPerPixel, markupText(t.text));
    return layer + "</g>\n";
}

// cairo's SVG with the text layer put in before its end.
std::string withTextLayer(const std::filesystem::path& svg, const std::vector<DrawnText>& texts, double pointsPerPixel,
                          std::string& error) {
    std::ifstream in(svg, std::ios::binary);
    std::string doc((std::istreambuf_iterator<char>(in)), {});
    const size_t end = doc.rfind("</svg>");
    if (end == std::string::npos) {
        error = "cairo wrote no whole SVG";
        return {};
    }
    return doc.insert(end, svgTextLayer(texts, pointsPerPixel));
}

// The file a document is written into, keeping the system's reason for a
// failed write: cairo's own file writer says only "error while writing to
// output stream", which hid a full disk.
class DocumentFile {
public:
    explicit DocumentFile(const std::filesystem::path& path)
        : file_(std::fopen(path.c_str(), "wbe")), err_(file_ ? 0 : errno) {}
    ~DocumentFile() {
        if (file_) std::fclose(file_);
    }
    DocumentFile(const DocumentFile&) = delete;
    DocumentFile& operator=(const DocumentFile&) = delete;

    /// Cairo's write function, `self` a DocumentFile.
    static cairo_status_t write(void* self, const unsigned char* data, unsigned int length) {
        return static_cast<DocumentFile*>(self)->append(data, length) ? CAIRO_STATUS_SUCCESS : CAIRO_STATUS_WRITE_ERROR;
    }
    bool append(const void* data, size_t length) {
        if (err_ == 0 && std::fwrite(data, 1, length, file_) != length) err_ = errno != 0 ? errno : EIO;
        return err_ == 0;
    }
    /// Closes the file: "" or "cannot be written: " and the system's reason,
    /// or cairo's (`status`) when the system gave none.
    std::string close(cairo_status_t status = CAIRO_STATUS_SUCCESS) {
        if (file_ && std::fclose(file_) != 0 && err_ == 0) err_ = errno;
        file_ = nullptr;
        if (err_ != 0) return "cannot be written: " + writeFailureReason(err_);
        if (status != CAIRO_STATUS_SUCCESS) return fmt::format("cannot be written: {}", cairo_status_to_string(status));
        return "";
    }

private:
    std::FILE* file_;
    int err_;
};

// The SVG cairo drew, at `drawnAt`, with the text layer added, written to `path`.
std::string finishSvg(const std::filesystem::path& drawnAt, const std::filesystem::path& path,
                      const std::vector<DrawnText>& texts, double pointsPerPixel) {
    std::string error;
    const std::string svg = withTextLayer(drawnAt, texts, pointsPerPixel, error);
    std::error_code ec;
    std::filesystem::remove(drawnAt, ec);
    if (!error.empty()) return error;
    DocumentFile out(path);
    out.append(svg.data(), svg.size());
    return out.close();
}

}  // namespace

namespace {

// The document, or why not (the words of the error at the still).
std::string documentOf(const PngImage8& still, const DocumentRequest& request, OverlayRecord* record) {
    if (still.channels != 3 && still.channels != 4)
        return fmt::format("a document needs an RGB or RGBA still, not one of {} channels", still.channels);
    const double pointsPerPixel = 72.0 / request.dpi;
    const double widthPt = still.width * pointsPerPixel, heightPt = still.height * pointsPerPixel;
    const std::filesystem::path drawnAt =
        request.format == DocumentFormat::Svg ? std::filesystem::path(request.path.string() + ".cairo") : request.path;
    DocumentFile pageFile(drawnAt);  // declared first: the page, destroyed before it, may still write
    Owned<cairo_surface_t> page(
        request.format == DocumentFormat::Pdf
            ? cairo_pdf_surface_create_for_stream(DocumentFile::write, &pageFile, widthPt, heightPt)
            : cairo_svg_surface_create_for_stream(DocumentFile::write, &pageFile, widthPt, heightPt));
    if (cairo_surface_status(page.get()) != CAIRO_STATUS_SUCCESS) return pageFile.close(cairo_surface_status(page.get()));
    if (request.format == DocumentFormat::Pdf) {
        // No clock in the file: the same still gives the same bytes.
        cairo_pdf_surface_set_metadata(page.get(), CAIRO_PDF_METADATA_CREATE_DATE, kDocumentDate);
        cairo_pdf_surface_set_metadata(page.get(), CAIRO_PDF_METADATA_CREATOR, "relief");
        // UTF-8, which cairo writes as the PDF's UTF-16: anything else fails the whole page ("input
        // string not valid UTF-8").
        if (!request.spec.title.empty()) {
            const std::string title = utf8Replaced(request.spec.title);
            cairo_pdf_surface_set_metadata(page.get(), CAIRO_PDF_METADATA_TITLE, title.c_str());
        }
    } else {
        cairo_svg_surface_set_document_unit(page.get(), CAIRO_SVG_UNIT_PT);
    }
    const Owned<cairo_t> cr(cairo_create(page.get()));
    cairo_scale(cr.get(), pointsPerPixel, pointsPerPixel);
    // The ray-traced image once, at its own pixels: drawn unscaled in pixel units, never resampled.
    const Owned<cairo_surface_t> image = surfaceOf(still);
    if (!image) return "cannot make a drawing surface";
    cairo_set_source_surface(cr.get(), image.get(), 0, 0);
    cairo_pattern_set_filter(cairo_get_source(cr.get()), CAIRO_FILTER_NEAREST);
    cairo_paint(cr.get());
    OverlayRecord drawn;
    if (request.overlays)
        drawn = paintOverlays(cr.get(), still.width, still.height, request.spec, request.facts, {true, pointsPerPixel});
    cairo_show_page(cr.get());
    cairo_surface_finish(page.get());
    if (std::string problem = pageFile.close(cairo_surface_status(page.get())); !problem.empty()) return problem;
    if (request.format == DocumentFormat::Svg)
        if (std::string problem = finishSvg(drawnAt, request.path, drawn.texts, pointsPerPixel); !problem.empty())
            return problem;
    if (record) *record = drawn;
    return {};
}

}  // namespace

bool writeDocument(const PngImage8& still, const DocumentRequest& request, const SourceLoc& at, Diagnostics& diags,
                   OverlayRecord* record) {
    OverlayRecord drawn;
    const std::string problem = documentOf(still, request, &drawn);
    if (!problem.empty()) diags.error(at, problem);
    else warnLeftOut(drawn, still.width, still.height, at, diags);
    if (record) *record = drawn;
    return problem.empty();
}

}  // namespace relief::annotate
