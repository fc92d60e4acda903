#include "io/vtk_writer.hpp"

#include "io/replace_file.hpp"

#include <vtkCellArray.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkRectilinearGrid.h>
#include <vtkStringArray.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLRectilinearGridWriter.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace mpile {

namespace {

vtkNew<vtkDoubleArray> scalar_array(const char* name, vtkIdType count) {
  vtkNew<vtkDoubleArray> array;
  array->SetName(name);
  array->SetNumberOfComponents(1);
  array->SetNumberOfTuples(count);
  return array;
}

vtkNew<vtkDoubleArray> vector_array(const char* name, vtkIdType count) {
  vtkNew<vtkDoubleArray> array;
  array->SetName(name);
  array->SetNumberOfComponents(3);
  array->SetNumberOfTuples(count);
  return array;
}

/// Writes a data set with an XML writer of its type: binary, zlib-compressed, appended data.
template <class Writer, class Data> void write_xml(Data& data, const std::string& path) {
  vtkNew<Writer> writer;
  writer->SetFileName(path.c_str());
  writer->SetDataModeToAppended();
  writer->EncodeAppendedDataOff(); // raw binary
  writer->SetCompressorTypeToZLib();
  writer->SetInputData(data);
  errno = 0;
  if (writer->Write() != 1) {
    const int reason = errno;
    // A snapshot cut short by a full disk is not left for ParaView to stumble on.
    std::error_code ignored;
    std::filesystem::remove(path, ignored);
    throw std::runtime_error("cannot write " + path + ": " +
                             (reason != 0 ? std::strerror(reason) : "the write failed"));
  }
}

} // namespace

void write_particles_vtu(const Scene& scene, const std::string& path) {
  const Particles& p = scene.particles;
  const auto n = static_cast<vtkIdType>(p.size());
  const bool theta = has_theta(scene.mode);

  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(n);
  vtkNew<vtkCellArray> vertices;
  for (vtkIdType i = 0; i < n; ++i) {
    points->SetPoint(i, p.r[static_cast<std::size_t>(i)], p.y[static_cast<std::size_t>(i)], 0.0);
    vertices->InsertNextCell(1, &i);
  }
  vtkNew<vtkUnstructuredGrid> grid;
  grid->SetPoints(points);
  grid->SetCells(VTK_VERTEX, vertices);

  const char* stress_names[] = {"sigma_rr", "sigma_yy",     "sigma_thth",
                                "sigma_ry", "sigma_ytheta", "sigma_rtheta"};
  for (std::size_t c = 0; c < 6; ++c) {
    auto array = scalar_array(stress_names[c], n);
    for (vtkIdType i = 0; i < n; ++i) {
      const auto k = static_cast<std::size_t>(i);
      array->SetValue(i, scene.materials[p.material[k]]->reported_stress(p.stress[k])[c]);
    }
    grid->GetPointData()->AddArray(array);
  }
  auto mean = scalar_array("p", n);
  auto deviatoric = scalar_array("q", n);
  auto density = scalar_array("density", n);
  auto velocity = vector_array("velocity", n);
  auto displacement = vector_array("displacement", n);
  auto mass = scalar_array("mass", n);
  auto volume = scalar_array("volume", n);
  vtkNew<vtkIntArray> id, body, material;
  id->SetName("id");
  id->SetNumberOfTuples(n);
  body->SetName("body");
  body->SetNumberOfTuples(n);
  material->SetName("material");
  material->SetNumberOfTuples(n);
  for (vtkIdType k = 0; k < n; ++k) {
    const auto i = static_cast<std::size_t>(k);
    const Stress stress = scene.materials[p.material[i]]->reported_stress(p.stress[i]);
    mean->SetValue(k, mean_pressure(stress));
    deviatoric->SetValue(k, deviatoric_stress(stress));
    density->SetValue(k, p.mass[i] / p.volume[i]);
    velocity->SetTuple3(k, p.v_r[i], p.v_y[i], theta ? p.v_theta[i] : 0.0);
    displacement->SetTuple3(k, p.r[i] - p.r0[i], p.y[i] - p.y0[i], theta ? p.u_theta[i] : 0.0);
    mass->SetValue(k, p.mass[i]);
    volume->SetValue(k, p.volume[i]);
    id->SetValue(k, p.id[i]);
    body->SetValue(k, p.body[i]);
    material->SetValue(k, p.material[i]);
  }
  for (vtkAbstractArray* array : std::initializer_list<vtkAbstractArray*>{
           mean, deviatoric, density, velocity, displacement, mass, volume, id, body, material}) {
    grid->GetPointData()->AddArray(array);
  }
  // State variables by name, one array per name whichever materials have it (two Hardening Soil
  // sands share gamma_p and p_p; one array per material overwrote the first with the second's
  // zeros); zero for particles whose material has no such variable.
  std::vector<std::string> state_names;
  std::vector<std::vector<int>> slot(scene.materials.size()); // [material][name] -> state index
  for (std::size_t m = 0; m < scene.materials.size(); ++m) {
    const auto names = scene.materials[m]->state_names();
    for (std::size_t s = 0; s < names.size(); ++s) {
      const auto at = std::find(state_names.begin(), state_names.end(), names[s]);
      const auto index = static_cast<std::size_t>(at - state_names.begin());
      if (at == state_names.end()) {
        state_names.push_back(names[s]);
      }
      slot[m].resize(state_names.size(), -1);
      slot[m][index] = static_cast<int>(s);
    }
  }
  for (std::size_t name = 0; name < state_names.size(); ++name) {
    auto array = scalar_array(state_names[name].c_str(), n);
    for (vtkIdType k = 0; k < n; ++k) {
      const auto i = static_cast<std::size_t>(k);
      const std::vector<int>& of = slot[p.material[i]];
      const int s = name < of.size() ? of[name] : -1;
      const double* state = p.state.data() + i * static_cast<std::size_t>(p.state_stride);
      array->SetValue(k, s >= 0 ? scene.materials[p.material[i]]->reported_state(
                                      s, state[static_cast<std::size_t>(s)])
                                : 0.0);
    }
    grid->GetPointData()->AddArray(array);
  }
  // The names behind the body and material numbers, as field data (ParaView's spreadsheet view
  // lists them; index k is number k).
  vtkNew<vtkStringArray> body_names, material_names;
  body_names->SetName("body_names");
  for (const std::string& name : scene.body_names) {
    body_names->InsertNextValue(name);
  }
  material_names->SetName("material_names");
  for (const std::string& name : scene.material_names) {
    material_names->InsertNextValue(name);
  }
  grid->GetFieldData()->AddArray(body_names);
  grid->GetFieldData()->AddArray(material_names);

  write_xml<vtkXMLUnstructuredGridWriter>(grid, path);
}

namespace {

std::string numbered_name(const char* prefix, std::size_t index, const char* extension) {
  std::ostringstream name;
  name << prefix << std::setw(6) << std::setfill('0') << index << extension;
  return name.str();
}

/// The contact of the last step at each node, summed over the contact pairs: the force of the soil
/// on the structure (N [/rad]), that force over the node's share of the outline (Pa: the traction
/// whose resultant it is, 0 where the node has no outline area), the surface holding most of that
/// area (an index into the field data contact_surface_names, "<structure>/<surface>"; -1 for
/// none) and the kind of contact (0 free, 1 sliding, 2 sticking). Along a pile's faces the
/// traction is the profile of radial stress and shaft friction the surface sums leave out.
void add_contact_arrays(const Scene& scene, vtkRectilinearGrid& grid) {
  const auto n = static_cast<vtkIdType>(scene.grid.node_count());
  auto force = vector_array("contact_force", n);
  auto traction = vector_array("contact_traction", n);
  vtkNew<vtkIntArray> surface, state;
  surface->SetName("contact_surface");
  surface->SetNumberOfTuples(n);
  state->SetName("contact_state");
  state->SetNumberOfTuples(n);
  force->Fill(0.0);
  traction->Fill(0.0);
  surface->Fill(-1);
  state->Fill(0);
  vtkNew<vtkStringArray> names;
  names->SetName("contact_surface_names");
  for (const ContactPair& pair : scene.contacts) {
    const std::size_t surfaces = pair.surface_count();
    const auto offset = static_cast<int>(names->GetNumberOfValues()); // this pair's first surface
    for (const std::string& name : pair.surfaces) {
      names->InsertNextValue(pair.name + "/" + name);
    }
    if (pair.node_force.size() != static_cast<std::size_t>(n)) {
      continue; // not sized yet: the solver has not been set up
    }
    for (vtkIdType k = 0; k < n; ++k) {
      const auto i = static_cast<std::size_t>(k);
      const auto& f = pair.node_force[i];
      double* total = force->GetPointer(3 * k);
      for (int d = 0; d < 3; ++d) {
        total[d] += f[static_cast<std::size_t>(d)];
      }
      state->SetValue(k, std::max<int>(state->GetValue(k), pair.state[i]));
      if (!pair.outline || pair.area[i] <= 0.0) {
        continue;
      }
      double* t = traction->GetPointer(3 * k);
      for (int d = 0; d < 3; ++d) {
        t[d] += f[static_cast<std::size_t>(d)] / pair.area[i];
      }
      const auto shares = pair.surface_area.begin() + static_cast<std::ptrdiff_t>(i * surfaces);
      const auto largest = std::max_element(shares, shares + static_cast<std::ptrdiff_t>(surfaces));
      surface->SetValue(k, offset + static_cast<int>(largest - shares));
    }
  }
  grid.GetPointData()->AddArray(force);
  grid.GetPointData()->AddArray(traction);
  grid.GetPointData()->AddArray(surface);
  grid.GetPointData()->AddArray(state);
  grid.GetFieldData()->AddArray(names);
}

void write_grid_vtr(const Scene& scene, const std::string& path) {
  const Grid& g = scene.grid;
  vtkNew<vtkDoubleArray> r, y, z;
  for (const double x : g.r_axis().nodes()) {
    r->InsertNextValue(x);
  }
  for (const double x : g.y_axis().nodes()) {
    y->InsertNextValue(x);
  }
  z->InsertNextValue(0.0);
  vtkNew<vtkRectilinearGrid> grid;
  grid->SetDimensions(g.nodes_r(), g.nodes_y(), 1);
  grid->SetXCoordinates(r);
  grid->SetYCoordinates(y);
  grid->SetZCoordinates(z);
  const auto n = static_cast<vtkIdType>(g.node_count());
  auto mass = scalar_array("mass", n);
  auto velocity = vector_array("velocity", n);
  for (vtkIdType k = 0; k < n; ++k) {
    const GridNode& node = g.nodes[static_cast<std::size_t>(k)];
    mass->SetValue(k, node.mass);
    // The theta unknown of a node is its angular velocity: v_theta = omega r.
    velocity->SetTuple3(k, node.velocity()[0], node.velocity()[1],
                        has_theta(scene.mode) ? node.velocity()[2] * g.node_r(static_cast<int>(k))
                                              : 0.0);
  }
  grid->GetPointData()->AddArray(mass);
  grid->GetPointData()->AddArray(velocity);
  if (scene.has_contact()) {
    add_contact_arrays(scene, *grid);
  }
  write_xml<vtkXMLRectilinearGridWriter>(grid, path);
}

} // namespace

SnapshotWriter::SnapshotWriter(std::string directory, bool grid_snapshots)
    : directory_(std::move(directory)), grid_snapshots_(grid_snapshots) {}

std::string SnapshotWriter::write(const Scene& scene, double time) {
  const std::string name = numbered_name("particles_", particles_.size(), ".vtu");
  write_particles_vtu(scene, directory_ + "/" + name);
  particles_.emplace_back(time, name);
  write_collection("particles.pvd", particles_);
  if (grid_snapshots_) {
    const std::string grid_name = numbered_name("grid_", grids_.size(), ".vtr");
    write_grid_vtr(scene, directory_ + "/" + grid_name);
    grids_.emplace_back(time, grid_name);
    write_collection("grid.pvd", grids_);
  }
  return name;
}

void SnapshotWriter::restore(std::vector<std::pair<double, std::string>> entries) {
  particles_ = std::move(entries);
  write_collection("particles.pvd", particles_);
  grids_.clear();
  if (grid_snapshots_) {
    for (std::size_t k = 0; k < particles_.size(); ++k) {
      grids_.emplace_back(particles_[k].first, numbered_name("grid_", k, ".vtr"));
    }
    write_collection("grid.pvd", grids_);
  }
  // The snapshot the interrupted run took as it stopped is listed by no index now; this run writes
  // its number again.
  std::error_code ignored;
  std::filesystem::remove(directory_ + "/" + numbered_name("particles_", particles_.size(), ".vtu"),
                          ignored);
  std::filesystem::remove(directory_ + "/" + numbered_name("grid_", particles_.size(), ".vtr"),
                          ignored);
}

void SnapshotWriter::write_collection(
    const std::string& name, const std::vector<std::pair<double, std::string>>& entries) const {
  const std::string path = directory_ + "/" + name;
  const std::string temporary = path + ".tmp";
  {
    std::ofstream out(temporary);
    out << "<?xml version=\"1.0\"?>\n"
        << "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
        << "  <Collection>\n";
    for (const auto& [time, file] : entries) {
      // The shortest text that reads back as the same double.
      char text[32];
      const auto end = std::to_chars(text, text + sizeof(text), time).ptr;
      out << "    <DataSet timestep=\"" << std::string(text, end)
          << "\" group=\"\" part=\"0\" file=\"" << file << "\"/>\n";
    }
    out << "  </Collection>\n</VTKFile>\n";
    errno = 0;
    out.close();
    if (!out) {
      const int reason = errno;
      std::error_code ignored;
      std::filesystem::remove(temporary, ignored);
      throw std::runtime_error("cannot write " + temporary + ": " +
                               (reason != 0 ? std::strerror(reason) : "the write failed"));
    }
  }
  replace_file(temporary, path);
}

} // namespace mpile
