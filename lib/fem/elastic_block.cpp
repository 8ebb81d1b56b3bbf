#include "lib/fem/elastic_block_impl.hpp"

namespace wr {

using petsc::check;

ElasticBlock::ElasticBlock(const BlockSpec& spec) : impl_(new Impl) {
  impl_->spec = spec;
  impl_->comm = spec.comm == MPI_COMM_NULL ? PETSC_COMM_WORLD : spec.comm;
  impl_->make_grid();
  impl_->amg = resolve_amg_hierarchy(spec.amg, nodes_on_this_host(impl_->comm, double(impl_->mesh->nodes())),
                                     double(physical_memory_bytes()));
  int ranks = 1;
  MPI_Comm_size(impl_->comm, &ranks);
  impl_->solver = resolve_linear_solver(spec.solver, double(impl_->mesh->nodes()), ranks, spec.use);
  impl_->assemble();
}

AmgHierarchy ElasticBlock::amg_hierarchy() const { return impl_->amg; }
LinearSolver ElasticBlock::linear_solver() const { return impl_->solver; }
std::string ElasticBlock::multigrid_description() const { return impl_->gmg ? impl_->gmg->describe() : std::string(); }
std::string ElasticBlock::multigrid_timing() const {
  if (!impl_->gmg) return {};
  char buf[64];
  std::snprintf(buf, sizeof buf, "; updates %.2f s", impl_->gmg->wall_update());
  return impl_->gmg->timing() + buf;
}

ElasticBlock::~ElasticBlock() {
  if (impl_->face_scatter) VecScatterDestroy(&impl_->face_scatter);
  if (impl_->face_u) VecDestroy(&impl_->face_u);
  if (impl_->u) VecDestroy(&impl_->u);
  impl_->gmg.reset();
  impl_->stiffness.reset();
  delete impl_;
}

const GradedMesh& ElasticBlock::mesh() const { return *impl_->mesh; }

std::size_t ElasticBlock::nodes() const { return std::size_t(impl_->mesh->nodes()); }

Mat ElasticBlock::assembled_stiffness() const {
  const auto* k = dynamic_cast<const FramedStiffness*>(impl_->stiffness.get());
  if (!k) throw std::logic_error("ElasticBlock::assembled_stiffness: the block was built without a matrix (--solver gmg)");
  return k->mat();
}
MPI_Comm ElasticBlock::comm() const { return impl_->comm; }

BlockState ElasticBlock::state() const {
  const Impl& m = *impl_;
  BlockState s;
  PetscInt n = 0;
  check(VecGetLocalSize(m.u, &n), "VecGetLocalSize");
  const PetscScalar* a;
  check(VecGetArrayRead(m.u, &a), "VecGetArrayRead");
  s.u.assign(a, a + n);
  check(VecRestoreArrayRead(m.u, &a), "VecRestoreArrayRead");
  s.active = m.active;
  s.lambda = m.lambda;
  s.softening_scale = m.softening_scale;
  return s;
}

void ElasticBlock::restore(const BlockState& s) {
  Impl& m = *impl_;
  PetscInt n = 0;
  check(VecGetLocalSize(m.u, &n), "VecGetLocalSize");
  if (s.u.size() != std::size_t(n))
    throw std::invalid_argument("ElasticBlock::restore: the state was taken from another block");
  PetscScalar* a;
  check(VecGetArray(m.u, &a), "VecGetArray");
  std::copy(s.u.begin(), s.u.end(), a);
  check(VecRestoreArray(m.u, &a), "VecRestoreArray");
  m.active = s.active;
  m.lambda = s.lambda;
  m.softening_scale = s.softening_scale;
}

std::vector<double> ElasticBlock::face_displacement() const {
  const Impl& m = *impl_;
  const std::size_t nfx = std::size_t(m.face_nx() + 1);
  std::vector<double> local(3 * nfx * std::size_t(m.face_ny() + 1), 0.0), global(local.size());
  const PetscInt rstart = 3 * PetscInt(m.own_begin);
  const PetscScalar* a;
  VecGetArrayRead(m.u, &a);
  for (const FaceNode& f : m.owned_face_nodes())
    for (int c = 0; c < 3; ++c) local[3 * (std::size_t(f.j) * nfx + std::size_t(f.i)) + c] = a[f.row[c] - rstart];
  VecRestoreArrayRead(m.u, &a);
  MPI_Allreduce(local.data(), global.data(), int(local.size()), MPI_DOUBLE, MPI_SUM, m.comm);
  return global;
}

void ElasticBlock::add_lifted_face_field(const std::vector<double>& field, int fnx, int fny) {
  if (fnx < 1 || fny < 1 || field.size() != 3 * std::size_t(fnx + 1) * std::size_t(fny + 1))
    throw std::invalid_argument("add_lifted_face_field: the field is not 3 x (fnx+1) x (fny+1) values");
  const double hx = impl_->spec.mesh.lx / fnx, hy = impl_->spec.mesh.ly / fny;
  impl_->for_each_lifted_node([&](const Vec3& x, double w, PetscScalar* d) {
    if (w <= 0) return;  // the fixed top
    const double sx = std::clamp(x.x / hx, 0.0, double(fnx)), sy = std::clamp(x.y / hy, 0.0, double(fny));
    const int i0 = std::min(int(sx), fnx - 1), j0 = std::min(int(sy), fny - 1);
    const double fx = sx - i0, fy = sy - j0;
    const double wt[4] = {(1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy};
    const std::size_t at[4] = {std::size_t(j0) * (fnx + 1) + i0, std::size_t(j0) * (fnx + 1) + i0 + 1,
                               std::size_t(j0 + 1) * (fnx + 1) + i0, std::size_t(j0 + 1) * (fnx + 1) + i0 + 1};
    for (int c = 0; c < 3; ++c) {
      double v = 0;
      for (int q = 0; q < 4; ++q) v += wt[q] * field[3 * at[q] + c];
      d[c] += w * v;
    }
  });
}

void ElasticBlock::write_vtu(const std::string& path) const {
  const Impl& m = *impl_;
  const GradedMesh& g = *m.mesh;
  VecScatter to_zero;
  Vec all;
  check(VecScatterCreateToZero(m.u, &to_zero, &all), "VecScatterCreateToZero");
  check(VecScatterBegin(to_zero, m.u, all, INSERT_VALUES, SCATTER_FORWARD), "VecScatterBegin");
  check(VecScatterEnd(to_zero, m.u, all, INSERT_VALUES, SCATTER_FORWARD), "VecScatterEnd");
  if (m.rank == 0) {
    const PetscScalar* ua;
    VecGetArrayRead(all, &ua);
    std::vector<double> points, disp;
    std::vector<std::int64_t> first(g.planes().size() + 1, 0);  // first point of each plane
    std::vector<GradedMesh::Parent> ps;
    for (std::size_t p = 0; p < g.planes().size(); ++p) {
      const int l = g.planes()[p].level;
      for (int j = 0; j <= g.cells_y(l); ++j)
        for (int i = 0; i <= g.cells_x(l); ++i) {
          const Vec3 x = g.position(int(p), i, j);
          points.insert(points.end(), {x.x, x.y, x.z});
          ps.clear();
          g.parents(int(p), i, j, ps);
          double d[3] = {0, 0, 0};
          for (const auto& q : ps)
            for (int c = 0; c < 3; ++c) d[c] += q.weight * ua[3 * q.id + c];
          disp.insert(disp.end(), {d[0], d[1], d[2]});
        }
      first[p + 1] = first[p] + std::int64_t(g.cells_x(l) + 1) * (g.cells_y(l) + 1);
    }
    VecRestoreArrayRead(all, &ua);
    std::vector<std::int64_t> conn, offsets;
    std::vector<std::uint8_t> types;
    static const int vtk_order[8] = {0, 1, 3, 2, 4, 5, 7, 6};  // VTK_HEXAHEDRON corner order
    for (int e = 0; e < g.layers(); ++e) {
      const int l = g.layer_level(e);
      for (int j = 0; j < g.cells_y(l); ++j)
        for (int i = 0; i < g.cells_x(l); ++i) {
          for (int c : vtk_order) {
            int p, pi, pj;
            g.corner(e, i, j, c, p, pi, pj);
            conn.push_back(first[p] + std::int64_t(pj) * (g.cells_x(g.planes()[p].level) + 1) + pi);
          }
          offsets.push_back(std::int64_t(conn.size()));
          types.push_back(12);
        }
    }
    write_vtu_file(path, points, disp, conn, offsets, types);
  }
  VecScatterDestroy(&to_zero);
  VecDestroy(&all);
}

}  // namespace wr
