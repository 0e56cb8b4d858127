// The container policy (container_policy.hpp): the bounds of a walk, the refusal of values kept
// outside the file, and the walk over an HDF5 file (plain HDF5 or MAT v7.3) that applies both
// before anything is read.
#include "io/container_policy.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <limits>
#include <unordered_map>
#include <unordered_set>

#include "core/json_text.hpp"
#include "io/containers.hpp"
#include "sysid/error.hpp"

namespace sysid::internal {
namespace {

constexpr const char* kSeeDocs = "docs/robustness.md, \"Files from elsewhere\"";

}  // namespace

// A path 32 groups deep can run to kilobytes: its end says where.
std::string Shown(const std::string& where) {
  constexpr std::size_t kKeep = 160;
  const std::string s = Printable(where, std::numeric_limits<std::size_t>::max());
  return s.size() <= kKeep ? s : "..." + s.substr(s.size() - kKeep);
}

void WalkBudget::Add(std::uint64_t n, const std::string& where) {
  Reserve(static_cast<double>(n), where);
  count_ += n;
}

void WalkBudget::Reserve(double n, const std::string& where) const {
  if (static_cast<double>(count_) + n <= static_cast<double>(kMaxContainerObjects)) return;
  throw InputError(fmt::format(
      "{}: more than {} objects to walk (links, groups, datasets, variables, cells, struct "
      "fields and object references, counted as the reader would visit them): refused before "
      "reading, at the bound on one file's objects ({})",
      where, kMaxContainerObjects, kSeeDocs));
}

void WalkBudget::Depth(int depth, const std::string& where) const {
  if (depth <= kMaxContainerDepth) return;
  throw InputError(fmt::format(
      "{}: nested more than {} levels deep (groups, cells, structs or object references): "
      "refused before reading, at the bound on a file's nesting ({})",
      where, kMaxContainerDepth, kSeeDocs));
}

void RequireStoredInFile(hid_t ds, const std::string& where) {
  Hdf5Handle dcpl(H5Dget_create_plist(ds), H5Pclose);
  if (!dcpl.ok())
    throw InputError(where + ": malformed HDF5 dataset: cannot read its creation properties");
  const H5D_layout_t layout = H5Pget_layout(dcpl.get());
  if (layout == H5D_VIRTUAL) {
    std::string from;
    char file[512] = {}, dataset[512] = {};
    size_t mappings = 0;
    if (H5Pget_virtual_count(dcpl.get(), &mappings) >= 0 && mappings > 0 &&
        H5Pget_virtual_filename(dcpl.get(), 0, file, sizeof file) >= 0 &&
        H5Pget_virtual_dsetname(dcpl.get(), 0, dataset, sizeof dataset) >= 0)
      from = fmt::format(", the first from '{}':'{}'", Printable(file), Printable(dataset));
    throw InputError(fmt::format(
        "{}: refused: a virtual dataset (its values are mapped from other datasets{}, possibly in "
        "other files); sysid reads only values stored in the file it is given (copy them into a "
        "plain dataset first)",
        where, from));
  }
  const int external = H5Pget_external_count(dcpl.get());
  if (external != 0) {
    char file[512] = {};
    off_t offset = 0;
    hsize_t size = 0;
    std::string named;
    if (external > 0 && H5Pget_external(dcpl.get(), 0, sizeof file, file, &offset, &size) >= 0)
      named = fmt::format(", the first '{}'", Printable(file));
    throw InputError(fmt::format(
        "{}: refused: a dataset with external storage (its values are the bytes of {} other "
        "file(s){}); sysid reads only values stored in the file it is given",
        where, external, named));
  }
  if (layout < 0 || layout >= H5D_NLAYOUTS)
    throw InputError(where + ": malformed HDF5 dataset: its storage layout is unknown");
}

namespace {

struct Link {
  std::string name;
  H5L_type_t type;
};

struct LinkList {
  std::vector<Link> links;
  std::uint64_t limit = 0;
  bool over = false;
};

// Collects a group's links up to `limit`: what the walk does with them comes after, in C++,
// where an error may throw (an exception must not cross HDF5's C frames).
herr_t CollectLink(hid_t, const char* name, const H5L_info_t* info, void* data) {
  auto* list = static_cast<LinkList*>(data);
  if (list->links.size() >= list->limit) {
    list->over = true;
    return 1;
  }
  list->links.push_back({name, info->type});
  return 0;
}

class Walker {
 public:
  Walker(hid_t file, const std::string& path) : file_(file), path_(path) {}

  Hdf5Walked Datasets() {
    H5O_info_t root;
    if (H5Oget_info2(file_, &root, H5O_INFO_BASIC) < 0)
      throw InputError(path_ + ": malformed HDF5 file: cannot read its root group");
    seen_.insert(root.addr);
    DatasetsIn(file_, "", 0);
    return std::move(out_);
  }

  Hdf5Walked Mat73() {
    H5O_info_t root;
    if (H5Oget_info2(file_, &root, H5O_INFO_BASIC) < 0)
      throw InputError(path_ + ": malformed or truncated MAT file: cannot read its root group");
    nodes_[root.addr] = Node{true, 1, 0};
    for (const Link& l : Links(file_, "/")) {
      if (l.name == "#refs#" || l.name == "#subsystem#") continue;
      const Node n = Mat73Link(file_, l, l.name, 1);
      if (n.size > 0) ++out_.root_variables;
    }
    return std::move(out_);
  }

 private:
  // What matio reads from one object: the objects it visits (itself included) and the levels
  // below it. `open` marks an object whose walk has not returned: reached again, it is a cycle.
  struct Node {
    bool open = false;
    std::uint64_t size = 0;
    int height = 0;
  };

  std::string Full(const std::string& where) const { return path_ + ":" + Shown(where); }

  std::vector<Link> Links(hid_t group, const std::string& where) {
    LinkList list;
    list.limit = kMaxContainerObjects - std::min(budget_.count(), kMaxContainerObjects);
    hsize_t index = 0;
    if (H5Literate(group, H5_INDEX_NAME, H5_ITER_INC, &index, &CollectLink, &list) < 0)
      throw InputError(Full(where) + ": malformed HDF5 file: cannot list the group's links");
    budget_.Add(list.links.size(), Full(where));
    if (list.over) budget_.Add(1, Full(where));  // throws: the bound, named
    return std::move(list.links);
  }

  // sysid's own reader: hard links, each object once.
  void DatasetsIn(hid_t group, const std::string& prefix, int depth) {
    budget_.Depth(depth, Full(prefix.empty() ? "/" : prefix));
    for (const Link& l : Links(group, prefix.empty() ? "/" : prefix)) {
      if (l.type != H5L_TYPE_HARD) continue;  // soft and external links are not followed
      const std::string where = prefix + "/" + l.name;
      H5O_info_t info;
      if (H5Oget_info_by_name2(group, l.name.c_str(), &info, H5O_INFO_BASIC, H5P_DEFAULT) < 0)
        continue;
      if (info.type == H5O_TYPE_DATASET) {
        if (seen_.insert(info.addr).second) {
          Hdf5Handle ds(H5Dopen2(group, l.name.c_str(), H5P_DEFAULT), H5Dclose);
          if (ds.ok()) RequireStoredInFile(ds.get(), Full(where));
        }
        out_.datasets.push_back({where, info.addr});
      } else if (info.type == H5O_TYPE_GROUP && seen_.insert(info.addr).second) {
        Hdf5Handle g(H5Gopen2(group, l.name.c_str(), H5P_DEFAULT), H5Gclose);
        if (g.ok()) DatasetsIn(g.get(), where, depth + 1);
      }
    }
  }

  // One link of a MAT v7.3 group (a root variable or a struct field), followed as matio does.
  // Returns an empty Node for a link matio does not read as a variable.
  Node Mat73Link(hid_t group, const Link& l, const std::string& where, int depth) {
    if (l.type == H5L_TYPE_EXTERNAL)
      throw InputError(Full(where) +
                       ": refused: an external link (to another file); sysid reads no file but "
                       "the one it is given");
    if (l.type != H5L_TYPE_HARD && l.type != H5L_TYPE_SOFT) return {};
    H5O_info_t info;
    if (H5Oget_info_by_name2(group, l.name.c_str(), &info, H5O_INFO_BASIC, H5P_DEFAULT) < 0) {
      if (depth == 1)
        throw InputError(path_ +
                         ": malformed or truncated MAT file: HDF5 cannot list the MAT v7.3 "
                         "file's variables");
      return {};  // a dangling soft link: nothing to read
    }
    if (info.type != H5O_TYPE_DATASET && info.type != H5O_TYPE_GROUP) return {};
    Node node;
    if (Seen(info, where, depth, &node)) return node;
    Hdf5Handle object(H5Oopen(group, l.name.c_str(), H5P_DEFAULT), H5Oclose);
    if (!object.ok()) return {};
    return Mat73Open(object.get(), info, where, depth);
  }

  // True when the walk has been at `info`'s object before: its node in *node, counted again (matio
  // reads it again). Throws when the walk is still inside it: a cycle.
  bool Seen(const H5O_info_t& info, const std::string& where, int depth, Node* node) {
    const auto it = nodes_.find(info.addr);
    if (it == nodes_.end()) return false;
    if (it->second.open)
      throw InputError(Full(where) +
                       ": refused: leads back to an object it is inside of (a cycle of links or "
                       "object references; matio would follow it until its stack ends)");
    budget_.Depth(depth + it->second.height, Full(where));
    Unfold(it->second.size, where);
    *node = it->second;
    return true;
  }

  Node Mat73Open(hid_t object, const H5O_info_t& info, const std::string& where, int depth) {
    budget_.Depth(depth, Full(where));
    nodes_[info.addr] = Node{true, 1, 0};
    Unfold(1, where);
    Node node{false, 1, 0};
    const auto add = [&](const Node& child) {
      node.size = std::min(node.size + child.size, kMaxContainerObjects + 1);
      if (child.size > 0) node.height = std::max(node.height, child.height + 1);
    };
    if (info.type == H5O_TYPE_GROUP) {
      for (const Link& l : Links(object, where))
        add(Mat73Link(object, l, where + "." + l.name, depth + 1));
    } else {
      RequireStoredInFile(object, Full(where));
      References(object, where, depth, add);
    }
    nodes_[info.addr] = node;
    return node;
  }

  // A dataset of object references (a cell array, a struct array's field): each target.
  template <typename Add>
  void References(hid_t ds, const std::string& where, int depth, Add&& add) {
    Hdf5Handle type(H5Dget_type(ds), H5Tclose);
    if (!type.ok() || H5Tget_class(type.get()) != H5T_REFERENCE ||
        H5Tequal(type.get(), H5T_STD_REF_OBJ) <= 0)
      return;
    Hdf5Handle space(H5Dget_space(ds), H5Sclose);
    const hssize_t n = space.ok() ? H5Sget_simple_extent_npoints(space.get()) : -1;
    if (n < 0) throw InputError(Full(where) + ": malformed MAT v7.3 cell: cannot read its size");
    if (n == 0 || H5Sget_simple_extent_type(space.get()) == H5S_NULL) return;
    budget_.Reserve(static_cast<double>(n), Full(where));
    std::vector<hobj_ref_t> refs(static_cast<std::size_t>(n));
    if (H5Dread(ds, H5T_STD_REF_OBJ, H5S_ALL, H5S_ALL, H5P_DEFAULT, refs.data()) < 0)
      throw InputError(Full(where) + ": malformed MAT v7.3 cell: cannot read its references");
    for (std::size_t k = 0; k < refs.size(); ++k) {
      const std::string child = fmt::format("{}{{{}}}", where, k + 1);
      budget_.Count(Full(child));
      Hdf5Handle target(H5Rdereference2(ds, H5P_DEFAULT, H5R_OBJECT, &refs[k]), H5Oclose);
      if (!target.ok()) continue;  // a null or dangling reference: matio reads it as empty
      H5O_info_t info;
      if (H5Oget_info2(target.get(), &info, H5O_INFO_BASIC) < 0) continue;
      if (info.type != H5O_TYPE_DATASET && info.type != H5O_TYPE_GROUP) continue;
      Node node;
      add(Seen(info, child, depth + 1, &node) ? node
                                              : Mat73Open(target.get(), info, child, depth + 1));
    }
  }

  // Counts `n` objects of matio's walk, an object it reads twice twice.
  void Unfold(std::uint64_t n, const std::string& where) {
    unfolded_ += n;
    if (unfolded_ > kMaxContainerObjects) {
      WalkBudget as_read;
      as_read.Add(unfolded_, Full(where));  // throws: the bound, named
    }
  }

  hid_t file_;
  std::string path_;
  WalkBudget budget_;
  Hdf5Walked out_;
  std::unordered_set<haddr_t> seen_;
  std::unordered_map<haddr_t, Node> nodes_;
  std::uint64_t unfolded_ = 0;
};

}  // namespace

Hdf5Walked WalkHdf5(hid_t file, const std::string& path, Hdf5Walk mode) {
  Walker walker(file, path);
  return mode == Hdf5Walk::kDatasets ? walker.Datasets() : walker.Mat73();
}

}  // namespace sysid::internal
