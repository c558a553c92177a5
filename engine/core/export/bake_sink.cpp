#include "core/export/bake_sink.h"

#include <chrono>
#include <filesystem>

#include "core/io/mesh_io.h"
#include "core/io/vdb_export.h"

namespace animorph {
namespace fs = std::filesystem;

namespace {

// s with every occurrence of from replaced by to (an error about a staged file names its final name).
std::string replaced(std::string s, const std::string& from, const std::string& to) {
  for (size_t at = s.find(from); !from.empty() && at != std::string::npos; at = s.find(from, at + to.size()))
    s.replace(at, from.size(), to);
  return s;
}

Status makeFolder(const fs::path& dir) {
  if (dir.empty()) return Status::success();
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) return Error{dir.string() + ": cannot create the folder: " + ec.message()};
  return Status::success();
}

}  // namespace

BakeSink::BakeSink(const BakeOutputs& o, int first, int count, double fps)
    : o_(o), first_(first), count_(std::max(count, 0)) {
  plyFiles_.resize(size_t(count_));
  objFiles_.resize(size_t(count_));
  vdbFiles_.resize(size_t(count_));
  if (o_.keepMeshes) kept_.resize(size_t(count_));
  if (o_.gltf.empty()) return;
  GltfSequenceOptions so;
  so.name = o_.prefix;
  so.fps = fps;
  so.firstFrame = first;
  sequence_ = std::make_unique<GltfSequenceWriter>(so);
  waiting_.resize(size_t(count_));
  ready_.assign(size_t(count_), 0);
}

Status BakeSink::open() const {
  if (o_.ply || o_.obj)
    if (Status st = makeFolder(o_.dir); !st) return st;
  if (!o_.gltf.empty())
    if (Status st = makeFolder(fs::path(o_.gltf).parent_path()); !st) return st;
  return makeFolder(o_.vdbDir);
}

bool BakeSink::wantsMeshes() const { return o_.ply || o_.obj || sequence_ || o_.keepMeshes; }

Status BakeSink::stageWrite(const std::string& finalPath, const std::function<Status(const std::string&)>& write) {
  std::string tmp;
  {
    std::lock_guard<std::mutex> lock(stagedMutex_);
    tmp = staged_.stage(finalPath);
  }
  Status st = write(tmp);
  if (!st) return Error{replaced(st.error(), tmp, finalPath)};
  return st;
}

Status BakeSink::addMesh(int k, TriangleMesh mesh) {
  const int f = first_ + k;
  if (o_.ply) {
    const std::string path = frameFileName(o_.dir, o_.prefix, f, "ply");
    if (Status st = stageWrite(path, [&](const std::string& tmp) { return writePly(mesh, tmp); }); !st) return st;
    plyFiles_[size_t(k)] = path;
  }
  if (o_.obj) {
    const std::string path = frameFileName(o_.dir, o_.prefix, f, "obj");
    if (Status st = stageWrite(path, [&](const std::string& tmp) { return writeObj(mesh, tmp); }); !st) return st;
    objFiles_[size_t(k)] = path;
  }
  if (sequence_) {
    std::lock_guard<std::mutex> lock(sequenceMutex_);
    waiting_[size_t(k)] = o_.keepMeshes ? mesh : std::move(mesh);
    ready_[size_t(k)] = 1;
    for (; nextForGltf_ < count_ && ready_[size_t(nextForGltf_)]; ++nextForGltf_) {
      Status added = sequence_->addFrame(waiting_[size_t(nextForGltf_)]);
      if (!added && sequenceError_.empty())
        sequenceError_ = "frame " + std::to_string(first_ + nextForGltf_) + ": " + added.error();
      waiting_[size_t(nextForGltf_)] = TriangleMesh{};
    }
  }
  if (o_.keepMeshes) kept_[size_t(k)] = std::move(mesh);
  return Status::success();
}

Status BakeSink::addVolume(int k, const LevelSetVoxels* band) {
  if (!band) {
    ++framesWithoutField_;
    return Status::success();
  }
  const std::string path = frameFileName(o_.vdbDir, o_.prefix, first_ + k, "vdb");
  if (Status st = stageWrite(path, [&](const std::string& tmp) { return writeVdbLevelSet(*band, tmp); }); !st)
    return st;
  vdbFiles_[size_t(k)] = path;
  return Status::success();
}

Status BakeSink::finish(BakeReport& report) {
  for (int k = 0; k < count_; ++k)
    for (const auto* files : {&plyFiles_, &objFiles_, &vdbFiles_})
      if (!(*files)[size_t(k)].empty()) report.files.push_back((*files)[size_t(k)]);
  report.framesWithoutField = framesWithoutField_;
  for (const std::string& v : vdbFiles_) report.levelSets += !v.empty();
  if (wantsVolumes() && report.levelSets == 0)
    return Error{"no frame of the range has an implicit field to write as a VDB level set (frames " +
                 std::to_string(first_) + ".." + std::to_string(first_ + count_ - 1) +
                 " are all skinned meshes: before B or after C)"};
  if (sequence_) {
    if (!sequenceError_.empty()) return Error{sequenceError_};
    const auto g0 = std::chrono::steady_clock::now();
    report.gltfMeshes = sequence_->meshCount();
    Status st = stageWrite(o_.gltf, [&](const std::string& tmp) { return writeGltfSequence(*sequence_, tmp); });
    if (!st) return st;
    report.gltfSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - g0).count();
    report.files.push_back(o_.gltf);
  }
  if (Status st = staged_.commit(); !st) return st;
  if (sequence_) {
    std::error_code ec;
    report.gltfMegabytes = double(fs::file_size(o_.gltf, ec)) / 1e6;
  }
  report.meshes = std::move(kept_);
  return Status::success();
}

}  // namespace animorph
