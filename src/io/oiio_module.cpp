// libfacet_openimageio.so: OpenImageIO behind image_file.h's interface, loaded at run time by
// openImageIO() (image_library.cpp) only when a format or a comparison needs it. It holds nothing of
// Facet's but this file, so that the program's start-up never binds OpenImageIO's libraries.
#include <memory>
#include <string>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include "io/image_file.h"

namespace facet {
namespace {

class OiioReader final : public ImageFileReader {
  public:
    explicit OiioReader(std::unique_ptr<OIIO::ImageInput> input) : input_(std::move(input)) {
        const OIIO::ImageSpec& spec = input_->spec();
        header_.width = spec.width;
        header_.height = spec.height;
        header_.depth = spec.depth;
        header_.channels = spec.nchannels;
        header_.alphaChannel = spec.alpha_channel;
        header_.eightBit = spec.format == OIIO::TypeDesc::UINT8;
        header_.floating = spec.format.is_floating_point();
        header_.deep = spec.deep;
    }

    const ImageHeader& header() const override { return header_; }

    bool read(int firstChannel, int endChannel, bool asFloat, void* out, std::size_t pixelStride) override {
        return input_->read_image(0, 0, firstChannel, endChannel,
                                  asFloat ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8, out,
                                  static_cast<OIIO::stride_t>(pixelStride));
    }

    std::string error() override { return input_->geterror(); }

  private:
    std::unique_ptr<OIIO::ImageInput> input_;
    ImageHeader header_;
};

class OiioLibrary final : public OpenImageIOLibrary {
  public:
    std::unique_ptr<ImageFileReader> open(const std::string& path, std::string& error) override {
        // Ask for the stored (unassociated) alpha: by default OpenImageIO premultiplies PNG colour by it.
        OIIO::ImageSpec config;
        config.attribute("oiio:UnassociatedAlpha", 1);
        OIIO::geterror();  // forget any earlier message
        std::unique_ptr<OIIO::ImageInput> input = OIIO::ImageInput::open(path, &config);
        if (!input) {
            error = OIIO::geterror();
            return nullptr;
        }
        return std::make_unique<OiioReader>(std::move(input));
    }

    std::string write(const std::string& path, const ImagePixels& pixels, int pngCompression,
                      ThreadPool*) override {
        OIIO::geterror();
        std::unique_ptr<OIIO::ImageOutput> output = OIIO::ImageOutput::create(path);
        if (!output) return OIIO::geterror();

        const OIIO::TypeDesc type = pixels.floating ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8;
        OIIO::ImageSpec spec(pixels.width, pixels.height, pixels.channels, type);
        spec.attribute("oiio:ColorSpace", pixels.floating ? "Linear" : "sRGB");
        // Store the values as given: without this, the PNG writer would divide colour by alpha.
        spec.attribute("oiio:UnassociatedAlpha", 1);
        spec.attribute("Software", "Facet");
        // No time of writing (OpenEXR and TIFF would stamp one): the same scene gives the same bytes.
        spec.attribute("DateTime", "");
        spec.attribute("png:compressionLevel", pngCompression);
        std::vector<std::uint8_t> codes;
        const void* data = pixels.data != nullptr
                               ? pixels.data
                               : static_cast<const void*>(pixels.codes(0, pixels.height, codes));
        if (!output->open(path, spec) || !output->write_image(type, data) || !output->close())
            return output->geterror();
        return "";
    }

    PixelComparison compare(const float* a, const float* b, int width, int height, int channels,
                            float threshold) override {
        // ImageBuf wraps caller memory without copying; the comparison only reads it.
        const OIIO::ImageSpec spec(width, height, channels, OIIO::TypeDesc::FLOAT);
        const OIIO::ImageBuf bufA(spec, const_cast<float*>(a)), bufB(spec, const_cast<float*>(b));
        const OIIO::ImageBufAlgo::CompareResults result =
            OIIO::ImageBufAlgo::compare(bufA, bufB, threshold, threshold);
        return {result.meanerror, result.maxerror, result.rms_error, static_cast<std::size_t>(result.nfail)};
    }
};

}  // namespace
}  // namespace facet

// The module's one entry point, found by name with dlsym.
extern "C" __attribute__((visibility("default"))) facet::OpenImageIOLibrary* facetOpenImageIO() {
    static facet::OiioLibrary library;
    return &library;
}
