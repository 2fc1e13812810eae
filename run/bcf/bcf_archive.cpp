#include "run/bcf/bcf_archive.hpp"

#include <zip.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>

#include "common/input_error.hpp"
#include "common/output_path.hpp"
#include "run/bcf/bcf_xml.hpp"

namespace isg::run::bcf {

namespace {

class ZipWriter {
 public:
  ZipWriter(const std::filesystem::path& path, std::time_t when) : path_(path) {
    zip_ = zipOpen64(path.c_str(), APPEND_STATUS_CREATE);
    if (zip_ == nullptr) fail(std::strerror(errno));
    std::tm utc{};
    gmtime_r(&when, &utc);
    // Zip's DOS times start in 1980.
    info_.tmz_date = {uInt(utc.tm_sec),  uInt(utc.tm_min),
                      uInt(utc.tm_hour), uInt(utc.tm_mday),
                      uInt(utc.tm_mon),  uInt(std::max(1980, utc.tm_year + 1900))};
  }
  ~ZipWriter() {
    if (zip_ != nullptr) zipClose(zip_, nullptr);
  }
  ZipWriter(const ZipWriter&) = delete;
  ZipWriter& operator=(const ZipWriter&) = delete;

  // `compress`: deflate (text); else stored (a PNG is compressed already).
  void add(const std::string& name, const std::string& bytes, bool compress) {
    zip_fileinfo info = info_;
    // A folder's entry carries the DOS directory attribute, as zip tools write one.
    if (!name.empty() && name.back() == '/') info.external_fa = 0x10;
    if (zipOpenNewFileInZip64(zip_, name.c_str(), &info, nullptr, 0, nullptr, 0, nullptr,
                              compress ? Z_DEFLATED : 0, compress ? Z_BEST_COMPRESSION : 0,
                              0) != ZIP_OK ||
        (!bytes.empty() &&
         zipWriteInFileInZip(zip_, bytes.data(), unsigned(bytes.size())) != ZIP_OK) ||
        zipCloseFileInZip(zip_) != ZIP_OK) {
      fail("cannot add " + name);
    }
  }

  void close() {
    const int status = zipClose(zip_, nullptr);
    zip_ = nullptr;
    if (status != ZIP_OK) fail("cannot finish the archive");
  }

 private:
  [[noreturn]] void fail(const std::string& why) const {
    throw common::InputError(path_.string(), "", "cannot write the BCF archive: " + why);
  }

  std::filesystem::path path_;
  zipFile zip_ = nullptr;
  zip_fileinfo info_{};
};

}  // namespace

void writeArchive(const std::filesystem::path& path, const std::vector<Topic>& topics,
                  const ArchiveOptions& options) {
  ZipWriter zip(path, options.created);
  zip.add("bcf.version", versionXml(), false);
  zip.add("extensions.xml", common::outputMark(common::OutputKind::kBcf, extensionsXml()), false);
  for (const Topic& topic : topics) {
    const std::string folder = topic.guid + "/";
    const std::string snapshot = options.snapshot ? options.snapshot(topic) : std::string();
    zip.add(folder, "", false);
    zip.add(folder + "markup.bcf",
            markupXml(topic, options.created, options.author, !snapshot.empty()), true);
    zip.add(folder + "viewpoint.bcfv", viewpointXml(topic), true);
    if (!snapshot.empty()) zip.add(folder + "snapshot.png", snapshot, false);
  }
  zip.close();
}

std::time_t creationTime() {
  const char* epoch = std::getenv("SOURCE_DATE_EPOCH");
  if (epoch == nullptr || *epoch == '\0') return std::time(nullptr);
  char* end = nullptr;
  errno = 0;
  const long long seconds = std::strtoll(epoch, &end, 10);
  if (errno != 0 || *end != '\0' || seconds < 0) {
    throw common::InputError(
        "SOURCE_DATE_EPOCH", "",
        std::string("expected a whole number of seconds since 1970, not \"") + epoch + "\"");
  }
  return std::time_t(seconds);
}

}  // namespace isg::run::bcf
