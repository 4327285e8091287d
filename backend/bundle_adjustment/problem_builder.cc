#include "backend/bundle_adjustment/problem_builder.h"

#include <glog/logging.h>

#include <algorithm>
#include <chrono>
#include <cstdint>

#include "backend/bundle_adjustment/floor_prior_cost.h"
#include "backend/bundle_adjustment/line_reprojection_cost.h"
#include "backend/bundle_adjustment/odometry_prior_cost.h"
#include "backend/bundle_adjustment/point_reprojection_cost.h"
#include "util/parallel.h"

namespace sfm {
namespace {

// The closest point of the line (point, unit direction) to x.
Eigen::Vector3d ProjectOntoLine(const Eigen::Vector3d& point, const Eigen::Vector3d& direction,
                                const Eigen::Vector3d& x) {
  return point + direction * direction.dot(x - point);
}

// A solved line back into its landmark: point and direction (the direction's sign kept), end0 at
// its junction point when it has one, otherwise end0 and end1 projected onto the line.
void WriteBackLine(const OrthonormalLine& parameters, const Landmarks& landmarks, LineLandmark* line) {
  Eigen::Vector3d point, direction;
  OrthonormalLineToPointDirection(parameters, &point, &direction);
  if (direction.dot(line->direction) < 0) direction = -direction;
  line->point = point;
  line->direction = direction;
  line->end0 = line->point_landmark >= 0 ? landmarks.points[line->point_landmark].position
                                         : ProjectOntoLine(point, direction, line->end0);
  line->end1 = ProjectOntoLine(point, direction, line->end1);
}

ceres::Solver::Options SolverOptions(const BundleAdjustmentOptions& options, ceres::LinearSolverType type) {
  ceres::Solver::Options solver_options;
  solver_options.linear_solver_type = type;
  solver_options.max_num_iterations = options.max_iterations;
  // One thread: Ceres 2.1's threaded evaluator sums the cost and gradient per thread and its Schur
  // eliminator adds into the reduced system under locks, in an order that varies from run to run,
  // and so did the results (docs/bundle_adjustment.md, "Determinism"). The parallelism is over the
  // landmarks' own small problems instead (RefineLinesOnFixedPoses).
  solver_options.num_threads = 1;
  solver_options.logging_type = ceres::SILENT;
  return solver_options;
}

// kAuto: a dense reduced system while it is small; above, the sparse one unless revisits fill it.
// A landmark seen in k frames adds up to k(k+1)/2 cells of 6x6 to the reduced system. Along a
// corridor each frame shares landmarks with a band of frames as deep as the view (70-80 cells per
// frame at 240-960 frames): cells and factor grow with the frames. On laps of a room the frames
// keep seeing the same landmarks: cells per frame grow with the laps (41, 80, 155 at 240, 480, 960
// frames; a third of all frame pairs) and the factor with their cube, while the iterative solver's
// products stay linear in the observations (room loop, 960 frames: CPU 89 -> 67 s, peak RSS 586 ->
// 304 MB). The factorisation wins below that (corridor 240 frames iterative: 3x the CPU).
ceres::LinearSolverType JointLinearSolver(const BundleAdjustmentOptions& options, size_t frames,
                                          size_t cells) {
  switch (options.linear_solver) {
    case BundleAdjustmentLinearSolver::kDenseSchur:
      return ceres::DENSE_SCHUR;
    case BundleAdjustmentLinearSolver::kSparseSchur:
      return ceres::SPARSE_SCHUR;
    case BundleAdjustmentLinearSolver::kIterativeSchur:
      return ceres::ITERATIVE_SCHUR;
    case BundleAdjustmentLinearSolver::kAuto:
      break;
  }
  if (static_cast<int>(frames) <= options.dense_schur_max_frames) return ceres::DENSE_SCHUR;
  return static_cast<double>(cells) > options.iterative_schur_min_cells_per_frame * frames
             ? ceres::ITERATIVE_SCHUR
             : ceres::SPARSE_SCHUR;
}

// The cells of the reduced system's upper triangle: the frame pairs (i <= j) that see one landmark.
class ReducedCells {
 public:
  explicit ReducedCells(size_t frames) : frames_(frames), seen_(frames * frames, false) {}
  template <typename Observations>
  void Add(const Observations& observations) {
    for (const auto& a : observations) {
      for (const auto& b : observations) {
        const size_t i = std::min(a.frame, b.frame), j = std::max(a.frame, b.frame);
        if (!seen_[i * frames_ + j]) {
          seen_[i * frames_ + j] = true;
          ++count_;
        }
      }
    }
  }
  size_t count() const { return count_; }

 private:
  size_t frames_;
  std::vector<bool> seen_;
  size_t count_ = 0;
};

// The lines of a joint solve (`joint`, indices in order) and those solved apart after it: a line
// with exactly two views has 4 residuals (the two end-point distances per view) for its 4 degrees
// of freedom; on any poses it fits both views exactly (the line where its two back-projected
// planes meet, which the observability check keeps at an angle), so its least cost is 0 on every
// pose and the joint minimum over the poses is the same without it. The floor prior's lines stay:
// their prior is a fifth and sixth residual, which the poses must then satisfy too.
void SplitLines(const Landmarks& landmarks, const FloorPriorState& floor, std::vector<int>* joint,
                std::vector<int>* apart) {
  std::vector<bool> on_floor(landmarks.lines.size(), false);
  if (floor.applied()) {
    for (int line : floor.landmarks().lines) on_floor[line] = true;
  }
  for (size_t i = 0; i < landmarks.lines.size(); ++i) {
    const bool two_view = landmarks.lines[i].observations.size() == 2;
    (two_view && !on_floor[i] ? apart : joint)->push_back(static_cast<int>(i));
  }
}

}  // namespace

std::unique_ptr<ceres::LossFunction> MakeImageLoss(const BundleAdjustmentOptions& options, double scale_px) {
  if (options.robust_loss == RobustLoss::kHuber) return std::make_unique<ceres::HuberLoss>(scale_px);
  return std::make_unique<ceres::CauchyLoss>(scale_px);
}

JointProblem::JointProblem(const AdjustmentSetup& setup, const FloorPriorState& floor, double loss_scale_px,
                           bool with_lines, AdjustmentParameters* parameters, const Landmarks& landmarks)
    : setup_(setup),
      parameters_(parameters),
      with_lines_(with_lines),
      loss_(MakeImageLoss(setup.options, loss_scale_px)),
      ordering_(std::make_shared<ceres::ParameterBlockOrdering>()) {
  const BundleAdjustmentOptions& options = setup.options;
  ceres::Problem::Options problem_options;
  problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  problem_options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  problem_ = std::make_unique<ceres::Problem>(problem_options);
  ceres::Problem& problem = *problem_;
  std::vector<PoseParameters>& poses = parameters->poses;

  // A pose is one block: the 7 numbers from its rotation on (see AddResidual).
  for (PoseParameters& pose : poses) {
    problem.AddParameterBlock(pose.rotation.data(), 7, &pose_manifold_);
    ordering_->AddElementToGroup(pose.rotation.data(), 1);
  }
  problem.SetParameterBlockConstant(poses[0].rotation.data());

  // Lines: all (with_lines), or all but the two-view lines solved apart after the solve.
  // joint_slot: a line's place among the problem's lines, or -1.
  if (with_lines) SplitLines(landmarks, floor, &joint_lines_, &apart_lines_);
  std::vector<int> joint_slot(landmarks.lines.size(), -1);
  for (size_t k = 0; k < joint_lines_.size(); ++k) joint_slot[joint_lines_[k]] = static_cast<int>(k);
  ReducedCells cells(poses.size());
  point_count_ = landmarks.points.size();
  const size_t line_count = joint_lines_.size();
  landmark_values_.resize(3 * point_count_ + 6 * line_count);
  for (size_t i = 0; i < point_count_; ++i) {
    const PointLandmark& point = landmarks.points[i];
    double* position = point_block(i);
    std::copy(point.position.data(), point.position.data() + 3, position);
    for (const PointObservation& observation : point.observations) {
      PoseParameters& pose = poses[observation.frame];
      AddResidual(
          PointReprojectionCost::Create(setup.camera, observation.pixel, observation.sqrt_information),
          loss_.get(), {pose.rotation.data(), pose.translation.data(), position});
    }
    cells.Add(point.observations);
    ordering_->AddElementToGroup(position, 0);
  }
  for (size_t i = 0; i < line_count; ++i) {
    const LineLandmark& line = landmarks.lines[joint_lines_[i]];
    double* line_parameters = line_block(i);
    const OrthonormalLine initial = OrthonormalLineFromPointDirection(line.point, line.direction);
    std::copy(initial.begin(), initial.end(), line_parameters);
    problem.AddParameterBlock(line_parameters, 6, &line_manifold_);
    for (const LineObservation& observation : line.observations) {
      PoseParameters& pose = poses[observation.frame];
      AddResidual(LineReprojectionCost::Create(setup.camera, observation.p0, observation.p1), loss_.get(),
                  {pose.rotation.data(), pose.translation.data(), line_parameters});
    }
    ordering_->AddElementToGroup(line_parameters, 0);
  }

  // The floor prior (whitened by floor_sigma_m; Huber at one sigma, so that a landmark selected
  // off the floor pulls with a bounded force) and the odometry's scale factor it observes.
  // A start whose scale is not 1 (an earlier adjustment's, which its floor prior rescaled) keeps
  // that scale in the odometry priors, held, until this run's floor frees it: otherwise the first
  // solves would pull the start back to the odometry's scale.
  // lambda and b are blocks of every odometry prior, held where they are not estimated (lambda
  // without the floor prior and in the line search's samples, b without with_bias): the odometry
  // prior then has the residuals and pose Jacobians of one without them (odometry_prior_cost.h).
  double* const scale = &parameters->odometry_scale;
  problem.AddParameterBlock(scale, 1);
  ordering_->AddElementToGroup(scale, 1);
  if (!floor.applied() || parameters->hold_scale) problem.SetParameterBlockConstant(scale);
  // Before the floor's decision (the coarse solve) of a long sequence whose rig may be on a level
  // floor: the coarse map stays level, so that its floor's height measures the odometry's scale.
  if (!floor.applied() && floor.bases_level_before_selection()) HoldBasesOnFloor();
  if (floor.applied()) {
    const FloorLandmarks& held = floor.landmarks();
    for (int point : held.points) {
      problem.AddResidualBlock(FloorPointCost::Create(options.floor_sigma_m), &floor_loss_,
                               point_block(point));
    }
    for (size_t k = 0; with_lines && k < held.lines.size(); ++k) {
      problem.AddResidualBlock(
          FloorLineCost::Create(floor.anchors()[k][0], floor.anchors()[k][1], options.floor_sigma_m),
          &floor_loss_, line_block(joint_slot[held.lines[k]]));
    }
    if (floor.base_on_floor()) HoldBasesOnFloor();
    problem.AddResidualBlock(OdometryScalePriorCost::Create(setup.noise.translation_sigma), nullptr, scale);
    // With nothing on the floor left, the scale it gave is kept.
    if (held.points.empty() && (!with_lines || held.lines.empty())) problem.SetParameterBlockConstant(scale);
  }

  // The odometry's rotation bias: a zero-mean prior with the noise model's per-frame rotation
  // sigma (a bias larger than the whole per-frame noise the model states is outside the model;
  // the steps' vision-determined rotations pin it far tighter, about sigma / sqrt(steps)).
  double* const bias = parameters->rotation_bias.data();
  problem.AddParameterBlock(bias, 3);
  ordering_->AddElementToGroup(bias, 1);
  if (parameters->with_bias) {
    problem.AddResidualBlock(OdometryRotationBiasPriorCost::Create(setup.noise.rotation_sigma), nullptr,
                             bias);
  } else {
    problem.SetParameterBlockConstant(bias);
  }
  // Counted over every line, in the solves without them too: the map decides the adjustment's
  // solver, so the coarse solve's points alone (fewer cells) do not take the factorisation.
  for (const LineLandmark& line : landmarks.lines) cells.Add(line.observations);
  reduced_cells_ = cells.count();
  // The odometry prior of every step (docs/bundle_adjustment.md, "Odometry prior").
  const std::vector<Pose3>& odometry = setup.odometry;
  const double rotation_sigma = setup.noise.rotation_sigma;
  for (size_t f = 0; f + 1 < poses.size(); ++f) {
    const Pose3 motion = odometry[f].Inverse() * odometry[f + 1];
    const OdometryStepSigmas sigmas = OdometryStepSigmasFor(motion.translation.norm(), setup.noise, options);
    AddResidual(OdometryPriorCost::Create(motion, rotation_sigma, sigmas.along_m, sigmas.across_m), nullptr,
                {poses[f].rotation.data(), poses[f].translation.data(), poses[f + 1].rotation.data(),
                 poses[f + 1].translation.data(), scale, bias});
  }
}

// BaseOnFloorCost on every pose but the first, which is held constant (its prior would be a constant).
void JointProblem::HoldBasesOnFloor() {
  const BundleAdjustmentOptions& options = setup_.options;
  const double tilt_sigma_rad = options.floor_sigma_m / setup_.base_T_camera.translation.z();
  std::vector<PoseParameters>& poses = parameters_->poses;
  for (size_t f = 1; f < poses.size(); ++f) {
    AddResidual(BaseOnFloorCost::Create(options.floor_sigma_m, tilt_sigma_rad), nullptr,
                {poses[f].rotation.data(), poses[f].translation.data()});
  }
}

void JointProblem::Solve(double function_tolerance, ceres::Solver::Summary* summary,
                         ceres::IterationCallback* callback) {
  ceres::Solver::Options solver_options = SolverOptions(
      setup_.options, JointLinearSolver(setup_.options, parameters_->poses.size(), reduced_cells_));
  solver_options.linear_solver_ordering = ordering_;
  // ITERATIVE_SCHUR's preconditioner: the reduced system's diagonal cells (the other solvers ignore it).
  solver_options.preconditioner_type = ceres::SCHUR_JACOBI;
  solver_options.function_tolerance = function_tolerance;
  // With lines, the steps crawl (for tens of iterations on the room loop, each lowering the cost
  // by about 2e-6 relative, 0.4 of the predicted decrease: the landmarks' nonlinearity); Ceres's
  // inner iterations re-solve each landmark on the step's poses and end the solve in a few.
  solver_options.use_inner_iterations = with_lines_;
  if (solver_options.use_inner_iterations) solver_options.inner_iteration_ordering = InnerIterationOrdering();
  // Ceres switches the inner iterations off for the rest of a solve once one of them lowers the
  // cost by less than inner_iteration_tolerance (relative, 1e-3 by default); the crawl then
  // resumes (corridor: 38 iterations of the solve after the outlier round, against 5). A gain
  // the solve's own stopping rule still counts keeps them on.
  solver_options.inner_iteration_tolerance = function_tolerance;
  if (callback != nullptr) solver_options.callbacks.push_back(callback);
  ceres::Solve(solver_options, problem_.get(), summary);
}

void JointProblem::WriteLandmarks(Landmarks* landmarks) const {
  for (size_t i = 0; i < point_count_; ++i) {
    landmarks->points[i].position = Eigen::Map<const Eigen::Vector3d>(landmark_values_.data() + 3 * i);
  }
  for (size_t i = 0; i < joint_lines_.size(); ++i) {
    const double* values = landmark_values_.data() + 3 * point_count_ + 6 * i;
    OrthonormalLine line_parameters;
    std::copy(values, values + 6, line_parameters.begin());
    WriteBackLine(line_parameters, *landmarks, &landmarks->lines[joint_lines_[i]]);
  }
}

// A pose among `blocks` is its rotation's and translation's pointers, next to each other; each
// such pair is given to Ceres as the pose's one 7-number block.
void JointProblem::AddResidual(ceres::CostFunction* cost, ceres::LossFunction* loss,
                               const std::vector<double*>& blocks) {
  std::vector<int> pose_starts;
  std::vector<double*> outer_blocks;
  for (size_t k = 0; k < blocks.size(); ++k) {
    outer_blocks.push_back(blocks[k]);
    if (k + 1 < blocks.size() && IsPoseRotation(blocks[k]) && blocks[k + 1] == blocks[k] + 4) {
      pose_starts.push_back(static_cast<int>(k));
      ++k;
    }
  }
  problem_->AddResidualBlock(new PoseBlockCost(cost, pose_starts), loss, outer_blocks);
}

// By address within the poses' vector: a search over the poses would make building a problem
// cost observations x frames.
bool JointProblem::IsPoseRotation(const double* block) const {
  const std::vector<PoseParameters>& poses = parameters_->poses;
  if (poses.empty()) return false;
  const auto address = reinterpret_cast<std::uintptr_t>(block);
  const auto first = reinterpret_cast<std::uintptr_t>(poses.front().rotation.data());
  if (address < first) return false;
  const std::uintptr_t offset = address - first;
  return offset % sizeof(PoseParameters) == 0 && offset / sizeof(PoseParameters) < poses.size();
}

// The group of Ceres's inner iterations: the landmarks (the points and lines of the problem, one
// independent set). After each step every landmark is re-solved on the step's poses, the variable
// projection of Ruhe & Wedin's algorithm II, which ends the crawl of the joint solves
// (docs/bundle_adjustment.md, "Solver"). Given explicitly: the ordering Ceres computes when given
// none comes from hash sets keyed by address, and its groups varied from run to run, and so did
// the results (docs/bundle_adjustment.md, "Determinism").
std::shared_ptr<ceres::ParameterBlockOrdering> JointProblem::InnerIterationOrdering() {
  auto ordering = std::make_shared<ceres::ParameterBlockOrdering>();
  // The landmark blocks start at their sizes' offsets, points then lines.
  for (size_t i = 0; i < point_count_; ++i) ordering->AddElementToGroup(landmark_values_.data() + 3 * i, 6);
  for (size_t j = 3 * point_count_; j < landmark_values_.size(); j += 6) {
    ordering->AddElementToGroup(landmark_values_.data() + j, 6);
  }
  return ordering;
}

double RefineLinesOnFixedPoses(const AdjustmentSetup& setup, double loss_scale_px,
                               std::vector<PoseParameters>* poses, Landmarks* landmarks,
                               const std::vector<int>* subset) {
  const auto start = std::chrono::steady_clock::now();
  const std::unique_ptr<ceres::LossFunction> loss = MakeImageLoss(setup.options, loss_scale_px);
  OrthonormalLineManifold line_manifold;
  ceres::Problem::Options problem_options;
  problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  problem_options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  const ceres::Solver::Options solver_options = SolverOptions(setup.options, ceres::DENSE_QR);
  const int count = static_cast<int>(subset ? subset->size() : landmarks->lines.size());
  // Each line is its own problem, solved in parallel (util/parallel.h); each reads copies of its
  // views' poses, writes only its own landmark and its own cost, and the costs are summed in the
  // lines' order: the same numbers on any thread count.
  std::vector<double> costs(count);
  ParallelFor(count, [&](int k) {
    LineLandmark& line = landmarks->lines[subset ? (*subset)[k] : k];
    OrthonormalLine parameters = OrthonormalLineFromPointDirection(line.point, line.direction);
    std::vector<PoseParameters> views;
    views.reserve(line.observations.size());
    for (const LineObservation& observation : line.observations) views.push_back((*poses)[observation.frame]);
    ceres::Problem problem(problem_options);
    problem.AddParameterBlock(parameters.data(), 6, &line_manifold);
    for (size_t v = 0; v < views.size(); ++v) {
      const LineObservation& observation = line.observations[v];
      problem.AddResidualBlock(LineReprojectionCost::Create(setup.camera, observation.p0, observation.p1),
                               loss.get(), views[v].rotation.data(), views[v].translation.data(),
                               parameters.data());
      problem.SetParameterBlockConstant(views[v].rotation.data());
      problem.SetParameterBlockConstant(views[v].translation.data());
    }
    ceres::Solver::Summary ceres_summary;
    ceres::Solve(solver_options, &problem, &ceres_summary);
    if (ceres_summary.IsSolutionUsable()) {
      WriteBackLine(parameters, *landmarks, &line);
      costs[k] = ceres_summary.final_cost;
    } else {
      costs[k] = ceres_summary.initial_cost;
    }
  });
  double cost = 0;
  for (const double line_cost : costs) cost += line_cost;
  VLOG(1) << "bundle adjustment: " << count << " lines solved alone on fixed poses in "
          << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() << " s";
  return cost;
}

}  // namespace sfm
