// A restart writes on into the NAME.h5 and NAME.xmf of the run it goes on from
// (result_writer.hpp, WrittenPosition): what that run wrote after its checkpoint goes
// (the step groups and the rows of /time and the history series), so that the files
// the restart leaves equal those of a run that was never stopped.
#include <hdf5.h>

#include <algorithm>
#include <string>
#include <vector>

#include "output/hdf5_support.hpp"
#include "output/result_writer_impl.hpp"

namespace exdyn::output {

using namespace hdf5;

namespace {

// Sets the series `path` (H,) or (H, columns) to `rows` rows.
void set_series_rows(const Hdf5Errors& errors, hid_t file, const std::string& path, hsize_t rows) {
  Handle dataset(errors.check(H5Dopen2(file, path.c_str(), H5P_DEFAULT), "cannot open dataset " + path),
                 H5Dclose);
  Handle space(errors.check(H5Dget_space(dataset.get()), "cannot read the dataspace of " + path), H5Sclose);
  hsize_t dims[2] = {0, 0};
  const int rank = H5Sget_simple_extent_dims(space.get(), dims, nullptr);
  if (rank < 1 || rank > 2) errors.fail("dataset " + path + " is not a series");
  if (dims[0] < rows)
    errors.fail("dataset " + path + " has " + std::to_string(dims[0]) +
                " rows, fewer than the checkpoint's " + std::to_string(rows) +
                ": the file is not the one the checkpoint was written with");
  dims[0] = rows;
  errors.check(H5Dset_extent(dataset.get(), dims), "cannot shorten dataset", path);
}

// /steps@output_fields: "from step 0: displacement, velocity; from step 400: displacement",
// replaced by each restart that changes the fields.
void write_field_sets(const Hdf5Errors& errors, hid_t file, const std::vector<FieldSet>& sets) {
  std::string text;
  for (const FieldSet& set : sets) {
    text += (text.empty() ? "" : "; ") + std::string("from step ") + std::to_string(set.from_step) + ":";
    for (std::size_t k = 0; k < set.fields.size(); ++k)
      for (const FieldLayout& layout : field_layouts)  // a field's dataset is named as the field
        if (layout.field == set.fields[k]) text += (k == 0 ? " " : ", ") + std::string(layout.dataset);
  }
  Handle steps(errors.check(H5Gopen2(file, "/steps", H5P_DEFAULT), "cannot open group /steps"), H5Gclose);
  if (H5Aexists(steps.get(), "output_fields") > 0)
    errors.check(H5Adelete(steps.get(), "output_fields"), "cannot replace attribute", "/steps@output_fields");
  Handle type(errors.check(H5Tcopy(H5T_C_S1), "cannot make a string type for /steps@output_fields"),
              H5Tclose);
  errors.check(H5Tset_size(type.get(), text.size()), "cannot size the string of", "/steps@output_fields");
  Handle space(errors.check(H5Screate(H5S_SCALAR), "cannot create dataspace for /steps@output_fields"),
               H5Sclose);
  Handle attribute(errors.check(H5Acreate2(steps.get(), "output_fields", type.get(), space.get(), H5P_DEFAULT,
                                           H5P_DEFAULT),
                                "cannot create attribute /steps@output_fields"),
                   H5Aclose);
  errors.check(H5Awrite(attribute.get(), type.get(), text.data()), "cannot write attribute",
               "/steps@output_fields");
}

herr_t collect_name(hid_t, const char* name, const H5L_info_t*, void* out) {
  static_cast<std::vector<std::string>*>(out)->emplace_back(name);
  return 0;
}

}  // namespace

void ResultWriter::Impl::resume(const WrittenPosition& position, long resume_step) {
  if (position.steps.size() != position.times.size() || position.field_sets.empty())
    throw std::logic_error("ResultWriter: a resume position of unequal steps and times, or no fields");
  // The fields of the steps before the restart, then this writer's from resume_step on.
  const auto canonical = [](const std::vector<const FieldLayout*>& layouts) {
    std::vector<input::OutputField> out;
    for (const FieldLayout* layout : layouts) out.push_back(layout->field);
    return out;
  };
  field_sets = position.field_sets;
  const bool changed = canonical(fields) != canonical(layouts_of(field_sets.back().fields));
  if (changed) field_sets.push_back({resume_step, canonical(fields)});
  {
    Hdf5File file(errors, Hdf5File::Mode::append);
    std::vector<std::string> groups;
    {
      Handle steps(errors.check(H5Gopen2(file.get(), "/steps", H5P_DEFAULT), "cannot open group /steps"),
                   H5Gclose);
      errors.check(H5Literate(steps.get(), H5_INDEX_NAME, H5_ITER_INC, nullptr, collect_name, &groups),
                   "cannot list group", "/steps");
    }
    std::vector<std::string> kept;
    for (const long step : position.steps) kept.push_back(step_group_name(step));
    std::sort(kept.begin(), kept.end());
    const auto is_kept = [&](const std::string& g) {
      return std::binary_search(kept.begin(), kept.end(), g);
    };
    if (std::size_t(std::count_if(groups.begin(), groups.end(), is_kept)) != kept.size())
      errors.fail(
          "lacks steps the checkpoint says were written: not the file the checkpoint was written with");
    for (const std::string& group : groups)
      if (!is_kept(group))
        errors.check(H5Ldelete(file.get(), ("/steps/" + group).c_str(), H5P_DEFAULT), "cannot remove group",
                     "/steps/" + group);
    set_series_rows(errors, file.get(), "/time", position.steps.size());
    for (const auto& column : history_columns)
      set_series_rows(errors, file.get(), std::string("/history/") + column.first, position.history_rows);
    for (const std::string& pair : contact_pairs)
      for (const char* series : {"/force", "/max_penetration", "/normal_force", "/tangential_force",
                                 "/normal_force_sum", "/tangential_force_sum"})
        set_series_rows(errors, file.get(), "/history/contact/" + pair + series, position.history_rows);
    for (const std::string& group : walls)
      set_series_rows(errors, file.get(), group + "/force", position.history_rows);
    if (changed) write_field_sets(errors, file.get(), field_sets);
    file.close();
  }
  steps_on_disk = position.steps.size();
  history_rows_on_disk = position.history_rows;
  written_steps = position.steps;
  written_times = position.times;
  if (!written_steps.empty()) last_step = written_steps.back(), last_time = written_times.back();
  step_xml.clear();
  for (std::size_t k = 0; k < written_steps.size(); ++k) {
    std::size_t set = 0;
    while (set + 1 < field_sets.size() && field_sets[set + 1].from_step <= written_steps[k]) ++set;
    step_xml.push_back(
        grid_xml(written_times[k], step_group_name(written_steps[k]), layouts_of(field_sets[set].fields)));
  }
  remove_stale_xdmf();
  if (!step_xml.empty()) write_xdmf();
}

}  // namespace exdyn::output
