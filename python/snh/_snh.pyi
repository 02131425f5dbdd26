"""
Stable Neo-Hookean flesh simulation on OpenCL devices.
"""
from __future__ import annotations
import numpy
import typing
__all__: list[str] = ['Animation', 'Barrier', 'Bone', 'Capsule', 'CgStop', 'Character', 'CharacterBoneOptions', 'CharacterBones', 'CharacterCacheSeries', 'CharacterClip', 'CharacterFrame', 'CharacterFrameOptions', 'CharacterPrepareOptions', 'CharacterReadOptions', 'CharacterRig', 'ChebyshevKind', 'ConstraintSet', 'ContactOptions', 'DeformationStatistics', 'DeviceInfo', 'DynamicsOptions', 'ElementFields', 'ElementType', 'Embedding', 'Error', 'FrameOptions', 'FrameRecord', 'HessianMode', 'Joint', 'LameParameters', 'Material', 'MaterialMap', 'MaterialModel', 'MaterialOptions', 'MaterialRegion', 'Mesh', 'MeshArray', 'MeshGroup', 'NewtonIteration', 'Obstacle', 'ObstacleType', 'PointCache', 'Precision', 'Preconditioner', 'ProductVariant', 'Reaction', 'Recovery', 'RecoveryAction', 'ResolvedConfiguration', 'ResolvedSetting', 'RigidTransform', 'Scene', 'SceneFile', 'SceneParameters', 'SceneProgress', 'SceneRun', 'SceneStep', 'ShapeDeviation', 'Simulation', 'SimulationState', 'SkinDeviation', 'SkinWeights', 'SolveOptions', 'SolveProfile', 'SolveResult', 'StableNeoHookean', 'StepResult', 'StepStatus', 'TriangleSurface', 'Voxelization', 'VoxelizeOptions', 'WeightPolicy', 'bone_constraints', 'bone_contains', 'boundary_surface', 'character_bones', 'character_cell', 'compute_element_fields', 'deformation_statistics', 'elastic_forces', 'element_fields_for_vtu', 'elements_in_box', 'elements_in_group', 'elements_in_sphere', 'elements_with_value', 'elements_with_value_in', 'embed', 'embedded_positions', 'enclosed_volume', 'identity_matrix4', 'linear_blend_skinning', 'list_devices', 'load_scene', 'lump_body_force', 'lumped_mass', 'make_box_lattice', 'make_material_map', 'make_scene', 'make_tet_box', 'make_voxel_cylinder', 'max_poisson_ratio', 'parse_animation_csv', 'parse_animation_json', 'prepare_character', 'read_animation', 'read_character', 'read_checkpoint', 'read_mdd', 'read_mesh', 'read_pc2', 'read_surface', 'run_character_frames', 'run_frames', 'run_scene', 'scene_defaults', 'scene_file_keys', 'scene_names', 'shape_deviation', 'split_hexes_into_tets', 'surface_area', 'to_rigid_transform', 'uniform_material', 'validate_closed_surface', 'vertex_spacing', 'vertices_in_box', 'vertices_in_group', 'vertices_in_sphere', 'vertices_on_plane', 'vertices_with_value', 'vertices_with_value_in', 'voxelize', 'write_checkpoint', 'write_mdd', 'write_mesh', 'write_obj', 'write_obj_surface', 'write_pc2', 'write_ply_surface', 'write_point_cache', 'write_pvd', 'write_scene_json', 'write_surface_ply', 'write_surface_vtu', 'write_vtu']
class Error(RuntimeError):
    pass
class ElementType:
    """
    Element kind: 8-node hexahedra or 4-node tetrahedra.
    
    Members:
    
      hex8
    
      tet4
    """
    __members__: typing.ClassVar[dict[str, ElementType]]
    hex8: typing.ClassVar[ElementType]
    tet4: typing.ClassVar[ElementType]
    def __eq__(self, other: typing.Any) -> bool:
        ...
    def __getstate__(self) -> int:
        ...
    def __hash__(self) -> int:
        ...
    def __index__(self) -> int:
        ...
    def __init__(self, value: int) -> None:
        ...
    def __int__(self) -> int:
        ...
    def __ne__(self, other: typing.Any) -> bool:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, state: int) -> None:
        ...
    def __str__(self) -> str:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def value(self) -> int:
        ...
class MeshGroup:
    """
    A named set of vertices and elements from a mesh file (Gmsh physical group, Medit reference).
    """
    def __init__(self, **kwargs) -> None:
        ...
    def __repr__(self) -> str:
        ...
    @property
    def dimension(self) -> int:
        """
        3 for a volume group; 0, 1, 2 for lower ones.
        """
    @dimension.setter
    def dimension(self, arg0: int) -> None:
        ...
    @property
    def elements(self) -> numpy.ndarray[numpy.int32]:
        """
        Element indices, int32 (m,).
        """
    @elements.setter
    def elements(self, arg1: typing.Any) -> None:
        ...
    @property
    def name(self) -> str:
        """
        Group name (empty for an unnamed Gmsh group).
        """
    @name.setter
    def name(self, arg0: str) -> None:
        ...
    @property
    def tag(self) -> int:
        """
        The file's number for the group.
        """
    @tag.setter
    def tag(self, arg0: int) -> None:
        ...
    @property
    def vertices(self) -> numpy.ndarray[numpy.int32]:
        """
        Vertex indices, int32 (n,).
        """
    @vertices.setter
    def vertices(self, arg1: typing.Any) -> None:
        ...
class MeshArray:
    """
    Values per vertex (point array) or per element (cell array).
    """
    def __init__(self, **kwargs) -> None:
        ...
    @property
    def components(self) -> int:
        """
        Values per vertex or element.
        """
    @components.setter
    def components(self, arg0: int) -> None:
        ...
    @property
    def name(self) -> str:
        """
        Array name.
        """
    @name.setter
    def name(self, arg0: str) -> None:
        ...
    @property
    def values(self) -> numpy.ndarray[numpy.float64]:
        """
        float64 (n,) for one component, else (n, components).
        """
    @values.setter
    def values(self, arg1: typing.Any) -> None:
        ...
class Mesh:
    """
    A volumetric mesh: rest positions (n, 3) float64 and elements (m, 8) hex8 or (m, 4) tet4.
    
    hex8 nodes follow VTK_HEXAHEDRON order; tet4 nodes are positively oriented.
    """
    def __init__(self, positions: typing.Any, elements: typing.Any, type: ElementType | None = None) -> None:
        """
        Builds a mesh from positions (n, 3) and elements (m, 8) or (m, 4); the element type follows the column count unless given. Raises ValueError for wrong shapes or dtypes, NaN/Inf positions and indices outside [0, n).
        """
    def __repr__(self) -> str:
        ...
    def copy(self) -> Mesh:
        """
        A deep copy.
        """
    def validate(self) -> list[int]:
        """
        Raises snh.Error naming the element or vertex at fault; returns the unused vertices.
        """
    def volume(self, positions: typing.Any = None) -> float:
        """
        Volume at positions (n, 3) (default: rest).
        """
    @property
    def cell_arrays(self) -> list[MeshArray]:
        """
        The file's cell arrays (MeshArray list; a copy).
        """
    @cell_arrays.setter
    def cell_arrays(self, arg0: list[MeshArray]) -> None:
        ...
    @property
    def element_count(self) -> int:
        """
        Number of elements m.
        """
    @property
    def elements(self) -> numpy.ndarray[numpy.int32]:
        """
        Element vertex indices, an int32 (m, 8) or (m, 4) copy.
        """
    @elements.setter
    def elements(self, arg1: typing.Any) -> None:
        ...
    @property
    def groups(self) -> list[MeshGroup]:
        """
        The file's groups (a list of MeshGroup; a copy).
        """
    @groups.setter
    def groups(self, arg0: list[MeshGroup]) -> None:
        ...
    @property
    def nodes_per_element(self) -> int:
        """
        8 for hex8, 4 for tet4.
        """
    @property
    def point_arrays(self) -> list[MeshArray]:
        """
        The file's point arrays (MeshArray list; a copy).
        """
    @point_arrays.setter
    def point_arrays(self, arg0: list[MeshArray]) -> None:
        ...
    @property
    def positions(self) -> numpy.ndarray[numpy.float64]:
        """
        Rest positions, a float64 (n, 3) copy.
        """
    @positions.setter
    def positions(self, arg1: typing.Any) -> None:
        ...
    @property
    def type(self) -> ElementType:
        """
        ElementType of every element.
        """
    @type.setter
    def type(self, arg0: ElementType) -> None:
        ...
    @property
    def vertex_count(self) -> int:
        """
        Number of vertices n.
        """
class ShapeDeviation:
    """
    Distance from the rest shape once rigid motion is removed.
    """
    @property
    def radius_of_gyration(self) -> float:
        """
        Of the rest shape.
        """
    @property
    def relative(self) -> float:
        """
        rms_distance / radius_of_gyration.
        """
    @property
    def rms_distance(self) -> float:
        """
        RMS distance after the best rigid fit.
        """
class Barrier:
    """
    Whether Stable Neo-Hookean carries the origin barrier term.
    
    Members:
    
      on
    
      off
    """
    __members__: typing.ClassVar[dict[str, Barrier]]
    off: typing.ClassVar[Barrier]
    on: typing.ClassVar[Barrier]
    def __eq__(self, other: typing.Any) -> bool:
        ...
    def __getstate__(self) -> int:
        ...
    def __hash__(self) -> int:
        ...
    def __index__(self) -> int:
        ...
    def __init__(self, value: int) -> None:
        ...
    def __int__(self) -> int:
        ...
    def __ne__(self, other: typing.Any) -> bool:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, state: int) -> None:
        ...
    def __str__(self) -> str:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def value(self) -> int:
        ...
class MaterialModel:
    """
    The material family (one kernel file each).
    
    Members:
    
      stable_neo_hookean
    
      fung
    
      arruda_boyce
    
      corotational
    
      fixed_corotational
    
      stvk_kikuuwe
    
      neohookean
    """
    __members__: typing.ClassVar[dict[str, MaterialModel]]
    arruda_boyce: typing.ClassVar[MaterialModel]
    corotational: typing.ClassVar[MaterialModel]
    fixed_corotational: typing.ClassVar[MaterialModel]
    fung: typing.ClassVar[MaterialModel]
    neohookean: typing.ClassVar[MaterialModel]
    stable_neo_hookean: typing.ClassVar[MaterialModel]
    stvk_kikuuwe: typing.ClassVar[MaterialModel]
    def __eq__(self, other: typing.Any) -> bool:
        ...
    def __getstate__(self) -> int:
        ...
    def __hash__(self) -> int:
        ...
    def __index__(self) -> int:
        ...
    def __init__(self, value: int) -> None:
        ...
    def __int__(self) -> int:
        ...
    def __ne__(self, other: typing.Any) -> bool:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, state: int) -> None:
        ...
    def __str__(self) -> str:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def value(self) -> int:
        ...
class LameParameters:
    """
    Small-strain Lame moduli.
    """
    def __init__(self, mu: float, lambda_: float) -> None:
        """
        Shear modulus mu and first Lame parameter lambda.
        """
    def __repr__(self) -> str:
        ...
    @property
    def lambda_(self) -> float:
        """
        First Lame parameter.
        """
    @lambda_.setter
    def lambda_(self, arg0: float) -> None:
        ...
    @property
    def mu(self) -> float:
        """
        Shear modulus.
        """
    @mu.setter
    def mu(self, arg0: float) -> None:
        ...
class MaterialOptions:
    """
    Model-specific settings for building a material from (E, nu).
    """
    def __init__(self, **kwargs) -> None:
        """
        Keyword arguments set the fields of the same names.
        """
    @property
    def alpha(self) -> float:
        """
        Chen and Barbic 2024 nonlinearity alpha.
        """
    @alpha.setter
    def alpha(self, arg0: float) -> None:
        ...
    @property
    def alpha_lambda(self) -> float | None:
        """
        Alpha of the lambda part, or None.
        """
    @alpha_lambda.setter
    def alpha_lambda(self, arg0: float | None) -> None:
        ...
    @property
    def arruda_boyce_beta1(self) -> float:
        """
        Arruda-Boyce beta1.
        """
    @arruda_boyce_beta1.setter
    def arruda_boyce_beta1(self, arg0: float) -> None:
        ...
    @property
    def arruda_boyce_beta2(self) -> float:
        """
        Arruda-Boyce beta2.
        """
    @arruda_boyce_beta2.setter
    def arruda_boyce_beta2(self, arg0: float) -> None:
        ...
    @property
    def barrier(self) -> Barrier | None:
        """
        Barrier (snh only), or None: on below nu 0.4.
        """
    @barrier.setter
    def barrier(self, arg0: Barrier | None) -> None:
        ...
    @property
    def fung_gamma(self) -> float:
        """
        gamma / mu_Lame.
        """
    @fung_gamma.setter
    def fung_gamma(self, arg0: float) -> None:
        ...
    @property
    def fung_mu1(self) -> float:
        """
        Fung exponent rate.
        """
    @fung_mu1.setter
    def fung_mu1(self, arg0: float) -> None:
        ...
    @property
    def kikuuwe_kappa(self) -> float:
        """
        kappa / mu_Lame.
        """
    @kikuuwe_kappa.setter
    def kikuuwe_kappa(self, arg0: float) -> None:
        ...
    @property
    def lambda_model(self) -> MaterialModel | None:
        """
        Model of the lambda part, or None.
        """
    @lambda_model.setter
    def lambda_model(self, arg0: MaterialModel | None) -> None:
        ...
    @property
    def neohookean_j0(self) -> float:
        """
        Inversion handling below J0.
        """
    @neohookean_j0.setter
    def neohookean_j0(self, arg0: float) -> None:
        ...
class StableNeoHookean:
    """
    The Stable Neo-Hookean energy's own parameters.
    """
    @staticmethod
    def from_lame(lame: LameParameters, barrier: Barrier | None = None) -> StableNeoHookean:
        """
        From the Lame moduli.
        """
    @staticmethod
    def from_youngs_modulus(youngs_modulus: float, poisson_ratio: float, barrier: Barrier | None = None) -> StableNeoHookean:
        """
        From E and nu with the paper's reparameterization (snh.Error for out-of-range values).
        """
    def lame(self) -> LameParameters:
        """
        The small-strain moduli this energy reproduces.
        """
    def poisson_ratio(self) -> float:
        """
        Small-strain Poisson's ratio.
        """
    def youngs_modulus(self) -> float:
        """
        Small-strain Young's modulus.
        """
    @property
    def barrier(self) -> bool:
        """
        Whether the barrier term is present.
        """
    @property
    def lambda_(self) -> float:
        """
        The energy's lambda.
        """
    @property
    def mu(self) -> float:
        """
        The energy's mu.
        """
class Material:
    """
    Any material model with its parameters.
    """
    @staticmethod
    def from_lame(lame: LameParameters, model: typing.Any = MaterialModel.stable_neo_hookean, options: MaterialOptions | None = None) -> Material:
        """
        A material of `model` with the given small-strain Lame moduli.
        """
    @staticmethod
    def from_youngs_modulus(youngs_modulus: float, poisson_ratio: float, model: typing.Any = MaterialModel.stable_neo_hookean, options: MaterialOptions | None = None) -> Material:
        """
        A material of `model` (MaterialModel or its name, e.g. 'snh') with small-strain moduli (E, nu); snh.Error for out-of-range values.
        """
    @typing.overload
    def __init__(self) -> None:
        """
        A zero material; build one with from_youngs_modulus or from_lame.
        """
    @typing.overload
    def __init__(self, snh: StableNeoHookean) -> None:
        """
        The Stable Neo-Hookean material.
        """
    def __repr__(self) -> str:
        ...
    def defined_for_inversion(self) -> bool:
        """
        Whether psi is defined for every F.
        """
    def lame(self) -> LameParameters:
        """
        The small-strain Lame moduli.
        """
    @property
    def barrier(self) -> bool:
        """
        Whether the snh barrier term is present.
        """
    @barrier.setter
    def barrier(self, arg0: bool) -> None:
        ...
    @property
    def c0(self) -> float:
        """
        First model-specific parameter.
        """
    @c0.setter
    def c0(self, arg0: float) -> None:
        ...
    @property
    def c1(self) -> float:
        """
        Second model-specific parameter.
        """
    @c1.setter
    def c1(self, arg0: float) -> None:
        ...
    @property
    def description(self) -> str:
        """
        E.g. 'snh' or 'snh alpha=1.5'.
        """
    @property
    def lambda_(self) -> float:
        """
        The energy's lambda.
        """
    @lambda_.setter
    def lambda_(self, arg0: float) -> None:
        ...
    @property
    def model(self) -> MaterialModel:
        """
        MaterialModel.
        """
    @model.setter
    def model(self, arg0: MaterialModel) -> None:
        ...
    @property
    def mu(self) -> float:
        """
        The energy's mu.
        """
    @mu.setter
    def mu(self, arg0: float) -> None:
        ...
class MaterialRegion:
    """
    A named set of elements with its own material.
    """
    def __init__(self, name: str, elements: typing.Any, material: Material) -> None:
        """
        Region `name` of `elements` with `material`.
        """
    @property
    def elements(self) -> numpy.ndarray[numpy.int32]:
        """
        Element indices, int32 (k,).
        """
    @elements.setter
    def elements(self, arg1: typing.Any) -> None:
        ...
    @property
    def material(self) -> Material:
        """
        The region's Material.
        """
    @material.setter
    def material(self, arg0: Material) -> None:
        ...
    @property
    def name(self) -> str:
        """
        Region name.
        """
    @name.setter
    def name(self, arg0: str) -> None:
        ...
class MaterialMap:
    """
    The material of every element: element e uses materials[element_material[e]].
    """
    @property
    def element_material(self) -> numpy.ndarray[numpy.int32]:
        """
        Index into materials per element, int32 (m,).
        """
    @element_material.setter
    def element_material(self, arg1: typing.Any) -> None:
        ...
    @property
    def materials(self) -> list[Material]:
        """
        Materials: 0 the base, k+1 region k (a copy).
        """
    @materials.setter
    def materials(self, arg0: list[Material]) -> None:
        ...
    @property
    def names(self) -> list[str]:
        """
        'base', then the regions' names.
        """
    @names.setter
    def names(self, arg0: list[str]) -> None:
        ...
    @property
    def uniform(self) -> bool:
        """
        True for one material.
        """
class Precision:
    """
    Working precision of the device kernels.
    
    Members:
    
      single
    
      double
    """
    __members__: typing.ClassVar[dict[str, Precision]]
    double: typing.ClassVar[Precision]
    single: typing.ClassVar[Precision]
    def __eq__(self, other: typing.Any) -> bool:
        ...
    def __getstate__(self) -> int:
        ...
    def __hash__(self) -> int:
        ...
    def __index__(self) -> int:
        ...
    def __init__(self, value: int) -> None:
        ...
    def __int__(self) -> int:
        ...
    def __ne__(self, other: typing.Any) -> bool:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, state: int) -> None:
        ...
    def __str__(self) -> str:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def value(self) -> int:
        ...
class Preconditioner:
    """
    Preconditioner of the conjugate gradient solves.
    
    Members:
    
      none
    
      block_jacobi
    
      multigrid
    """
    __members__: typing.ClassVar[dict[str, Preconditioner]]
    block_jacobi: typing.ClassVar[Preconditioner]
    multigrid: typing.ClassVar[Preconditioner]
    none: typing.ClassVar[Preconditioner]
    def __eq__(self, other: typing.Any) -> bool:
        ...
    def __getstate__(self) -> int:
        ...
    def __hash__(self) -> int:
        ...
    def __index__(self) -> int:
        ...
    def __init__(self, value: int) -> None:
        ...
    def __int__(self) -> int:
        ...
    def __ne__(self, other: typing.Any) -> bool:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, state: int) -> None:
        ...
    def __str__(self) -> str:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def value(self) -> int:
        ...
class ProductVariant:
    """
    How Hessian products are computed.
    
    Members:
    
      cached
    
      recompute
    
      element_matrices
    
      assembled
    """
    __members__: typing.ClassVar[dict[str, ProductVariant]]
    assembled: typing.ClassVar[ProductVariant]
    cached: typing.ClassVar[ProductVariant]
    element_matrices: typing.ClassVar[ProductVariant]
    recompute: typing.ClassVar[ProductVariant]
    def __eq__(self, other: typing.Any) -> bool:
        ...
    def __getstate__(self) -> int:
        ...
    def __hash__(self) -> int:
        ...
    def __index__(self) -> int:
        ...
    def __init__(self, value: int) -> None:
        ...
    def __int__(self) -> int:
        ...
    def __ne__(self, other: typing.Any) -> bool:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, state: int) -> None:
        ...
    def __str__(self) -> str:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def value(self) -> int:
        ...
class HessianMode:
    """
    Projected Hessian always, or the true one near the solution.
    
    Members:
    
      projected
    
      adaptive
    """
    __members__: typing.ClassVar[dict[str, HessianMode]]
    adaptive: typing.ClassVar[HessianMode]
    projected: typing.ClassVar[HessianMode]
    def __eq__(self, other: typing.Any) -> bool:
        ...
    def __getstate__(self) -> int:
        ...
    def __hash__(self) -> int:
        ...
    def __index__(self) -> int:
        ...
    def __init__(self, value: int) -> None:
        ...
    def __int__(self) -> int:
        ...
    def __ne__(self, other: typing.Any) -> bool:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, state: int) -> None:
        ...
    def __str__(self) -> str:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def value(self) -> int:
        ...
class ChebyshevKind:
    """
    Polynomial of the multigrid smoother.
    
    Members:
    
      first
    
      fourth
    
      optimized_fourth
    """
    __members__: typing.ClassVar[dict[str, ChebyshevKind]]
    first: typing.ClassVar[ChebyshevKind]
    fourth: typing.ClassVar[ChebyshevKind]
    optimized_fourth: typing.ClassVar[ChebyshevKind]
    def __eq__(self, other: typing.Any) -> bool:
        ...
    def __getstate__(self) -> int:
        ...
    def __hash__(self) -> int:
        ...
    def __index__(self) -> int:
        ...
    def __init__(self, value: int) -> None:
        ...
    def __int__(self) -> int:
        ...
    def __ne__(self, other: typing.Any) -> bool:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, state: int) -> None:
        ...
    def __str__(self) -> str:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def value(self) -> int:
        ...
class ObstacleType:
    """
    Kinematic obstacle shape.
    
    Members:
    
      plane
    
      sphere
    
      cylinder
    """
    __members__: typing.ClassVar[dict[str, ObstacleType]]
    cylinder: typing.ClassVar[ObstacleType]
    plane: typing.ClassVar[ObstacleType]
    sphere: typing.ClassVar[ObstacleType]
    def __eq__(self, other: typing.Any) -> bool:
        ...
    def __getstate__(self) -> int:
        ...
    def __hash__(self) -> int:
        ...
    def __index__(self) -> int:
        ...
    def __init__(self, value: int) -> None:
        ...
    def __int__(self) -> int:
        ...
    def __ne__(self, other: typing.Any) -> bool:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, state: int) -> None:
        ...
    def __str__(self) -> str:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def value(self) -> int:
        ...
class DeviceInfo:
    """
    An OpenCL device.
    """
    def __repr__(self) -> str:
        ...
    @property
    def compute_units(self) -> int:
        """
        Compute units.
        """
    @property
    def global_memory_bytes(self) -> int:
        """
        Global memory in bytes.
        """
    @property
    def has_fp64(self) -> bool:
        """
        Whether it supports double precision.
        """
    @property
    def is_gpu(self) -> bool:
        """
        Whether the device is a GPU.
        """
    @property
    def name(self) -> str:
        """
        Device name.
        """
    @property
    def platform(self) -> str:
        """
        Platform name.
        """
    @property
    def version(self) -> str:
        """
        OpenCL version string.
        """
class StepStatus:
    """
    How a load or time step's Newton solve ended.
    
    Members:
    
      none
    
      converged
    
      max_newton_iterations
    
      line_search_failed
    
      stagnated
    
      non_finite_state
    
      cancelled
    
      inverted_elements
    """
    __members__: typing.ClassVar[dict[str, StepStatus]]
    cancelled: typing.ClassVar[StepStatus]
    converged: typing.ClassVar[StepStatus]
    inverted_elements: typing.ClassVar[StepStatus]
    line_search_failed: typing.ClassVar[StepStatus]
    max_newton_iterations: typing.ClassVar[StepStatus]
    non_finite_state: typing.ClassVar[StepStatus]
    none: typing.ClassVar[StepStatus]
    stagnated: typing.ClassVar[StepStatus]
    @staticmethod
    def __str__(*args, **kwargs):
        """
        (self: snh._snh.StepStatus) -> str
        """
    def __eq__(self, other: typing.Any) -> bool:
        ...
    def __getstate__(self) -> int:
        ...
    def __hash__(self) -> int:
        ...
    def __index__(self) -> int:
        ...
    def __init__(self, value: int) -> None:
        ...
    def __int__(self) -> int:
        ...
    def __ne__(self, other: typing.Any) -> bool:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, state: int) -> None:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def value(self) -> int:
        ...
class CgStop:
    """
    Why a Newton iteration's conjugate gradient solve stopped.
    
    Members:
    
      none
    
      converged
    
      max_iterations
    
      negative_curvature
    
      breakdown
    """
    __members__: typing.ClassVar[dict[str, CgStop]]
    breakdown: typing.ClassVar[CgStop]
    converged: typing.ClassVar[CgStop]
    max_iterations: typing.ClassVar[CgStop]
    negative_curvature: typing.ClassVar[CgStop]
    none: typing.ClassVar[CgStop]
    @staticmethod
    def __str__(*args, **kwargs):
        """
        (self: snh._snh.CgStop) -> str
        """
    def __eq__(self, other: typing.Any) -> bool:
        ...
    def __getstate__(self) -> int:
        ...
    def __hash__(self) -> int:
        ...
    def __index__(self) -> int:
        ...
    def __init__(self, value: int) -> None:
        ...
    def __int__(self) -> int:
        ...
    def __ne__(self, other: typing.Any) -> bool:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, state: int) -> None:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def value(self) -> int:
        ...
class RecoveryAction:
    """
    What the Newton solver did to get past trouble.
    
    Members:
    
      cg_breakdown_steepest_descent
    
      non_finite_direction_steepest_descent
    
      non_descent_steepest_descent
    
      cg_breakdown_partial_direction
    
      line_search_steepest_descent
    
      line_search_steepest_descent_failed
    
      shorter_step
    
      extended_step
    
      double_fallback
    
      inverted_equilibrium_perturbed
    
      inverted_equilibrium_kept
    """
    __members__: typing.ClassVar[dict[str, RecoveryAction]]
    cg_breakdown_partial_direction: typing.ClassVar[RecoveryAction]
    cg_breakdown_steepest_descent: typing.ClassVar[RecoveryAction]
    double_fallback: typing.ClassVar[RecoveryAction]
    extended_step: typing.ClassVar[RecoveryAction]
    inverted_equilibrium_kept: typing.ClassVar[RecoveryAction]
    inverted_equilibrium_perturbed: typing.ClassVar[RecoveryAction]
    line_search_steepest_descent: typing.ClassVar[RecoveryAction]
    line_search_steepest_descent_failed: typing.ClassVar[RecoveryAction]
    non_descent_steepest_descent: typing.ClassVar[RecoveryAction]
    non_finite_direction_steepest_descent: typing.ClassVar[RecoveryAction]
    shorter_step: typing.ClassVar[RecoveryAction]
    @staticmethod
    def __str__(*args, **kwargs):
        """
        (self: snh._snh.RecoveryAction) -> str
        """
    def __eq__(self, other: typing.Any) -> bool:
        ...
    def __getstate__(self) -> int:
        ...
    def __hash__(self) -> int:
        ...
    def __index__(self) -> int:
        ...
    def __init__(self, value: int) -> None:
        ...
    def __int__(self) -> int:
        ...
    def __ne__(self, other: typing.Any) -> bool:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, state: int) -> None:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def value(self) -> int:
        ...
class Recovery:
    """
    One recovery of a Newton iteration (read-only).
    """
    def __repr__(self) -> str:
        ...
    def __str__(self) -> str:
        ...
    @property
    def action(self) -> RecoveryAction:
        ...
    @property
    def factor(self) -> int:
        """
        extended_step: the step's factor.
        """
    @property
    def float_status(self) -> StepStatus:
        """
        double_fallback: how the float solve ended.
        """
class NewtonIteration:
    """
    One Newton iteration's record (read-only).
    """
    def __repr__(self) -> str:
        ...
    @property
    def cg_iterations(self) -> int:
        """
        CG iterations of this solve.
        """
    @property
    def cg_relative_residual(self) -> float:
        """
        CG's relative residual.
        """
    @property
    def cg_stop(self) -> CgStop:
        """
        Why CG stopped (CgStop).
        """
    @property
    def energy(self) -> float:
        """
        Energy.
        """
    @property
    def iteration(self) -> int:
        """
        Iteration within the step.
        """
    @property
    def projected(self) -> bool:
        """
        Whether the Hessian was the PSD projection.
        """
    @property
    def recovery(self) -> list[Recovery]:
        """
        What the solver did to get past trouble: a list of Recovery, empty if nothing.
        """
    @property
    def recovery_text(self) -> str:
        """
        The recoveries as text (the names of the JSON output), or ''.
        """
    @property
    def residual_norm(self) -> float:
        """
        Residual before this update.
        """
    @property
    def seconds(self) -> float:
        """
        Wall time since the solve began.
        """
    @property
    def steepest_descent(self) -> bool:
        """
        Whether the preconditioned steepest descent replaced CG's direction.
        """
    @property
    def step(self) -> int:
        """
        Load or time step.
        """
    @property
    def step_length(self) -> float:
        """
        Line-search alpha accepted (0 if none).
        """
class SolveProfile:
    """
    Where a solve's time went, in seconds (read-only).
    """
    @property
    def blocking_readbacks(self) -> int:
        """
        Reads from the device the host waited for.
        """
    @property
    def bytes_to_device(self) -> int:
        ...
    @property
    def bytes_to_host(self) -> int:
        ...
    @property
    def cg_iterations_past_convergence(self) -> int:
        ...
    @property
    def cg_vector_work(self) -> float:
        ...
    @property
    def kernel_launches(self) -> int:
        """
        Kernels queued on the device.
        """
    @property
    def kernels(self) -> dict[str, float]:
        """
        Seconds per OpenCL kernel, by name.
        """
    @property
    def line_search_energies(self) -> float:
        ...
    @property
    def linearization(self) -> float:
        ...
    @property
    def other(self) -> float:
        ...
    @property
    def preconditioner_apply(self) -> float:
        ...
    @property
    def preconditioner_setup(self) -> float:
        ...
    @property
    def products(self) -> float:
        ...
    @property
    def total(self) -> float:
        """
        Wall time less the callbacks.
        """
    @property
    def transfers(self) -> float:
        ...
class StepResult:
    """
    One load or time step's outcome (read-only).
    """
    def __repr__(self) -> str:
        ...
    @property
    def cg_iterations(self) -> int:
        ...
    @property
    def contacts(self) -> int:
        ...
    @property
    def converged(self) -> bool:
        ...
    @property
    def fallback(self) -> str:
        """
        What fallback_to_double did, or ''.
        """
    @property
    def inverted_elements(self) -> int:
        """
        Elements with J <= 0 at the step's end.
        """
    @property
    def max_penetration(self) -> float:
        ...
    @property
    def max_self_penetration(self) -> float:
        ...
    @property
    def min_j(self) -> float:
        """
        The smallest J at the step's end.
        """
    @property
    def newton_iterations(self) -> int:
        ...
    @property
    def precision_used(self) -> Precision:
        """
        The Precision of the solve this result reports.
        """
    @property
    def preconditioner_builds(self) -> int:
        ...
    @property
    def profile(self) -> SolveProfile:
        ...
    @property
    def residual_norm(self) -> float:
        ...
    @property
    def seconds(self) -> float:
        ...
    @property
    def self_contacts(self) -> int:
        ...
    @property
    def status(self) -> StepStatus:
        """
        A StepStatus; str() gives its name.
        """
    @property
    def step(self) -> int:
        ...
    @property
    def time(self) -> float:
        """
        With dynamics: simulated time at the step's end.
        """
    @property
    def warnings(self) -> list[str]:
        """
        Damage the step shows (empty: a clean step).
        """
class SolveResult:
    """
    A solve's outcome (read-only).
    """
    def __repr__(self) -> str:
        ...
    @property
    def cancelled(self) -> bool:
        """
        The progress callback stopped the solve.
        """
    @property
    def converged(self) -> bool:
        ...
    @property
    def device(self) -> DeviceInfo:
        ...
    @property
    def device_memory_bytes(self) -> int:
        ...
    @property
    def final_residual_norm(self) -> float:
        ...
    @property
    def history(self) -> list[NewtonIteration]:
        """
        NewtonIteration records.
        """
    @property
    def inverted_elements(self) -> int:
        ...
    @property
    def kernel_specialization(self) -> str:
        ...
    @property
    def max_j(self) -> float:
        ...
    @property
    def min_j(self) -> float:
        ...
    @property
    def multigrid_chebyshev(self) -> ChebyshevKind | None:
        ...
    @property
    def multigrid_float_cycle(self) -> bool:
        ...
    @property
    def multigrid_smoother_degree(self) -> int | None:
        ...
    @property
    def positions(self) -> numpy.ndarray[numpy.float64]:
        """
        Positions after the last step, float64 (n, 3).
        """
    @property
    def preconditioner(self) -> Preconditioner:
        ...
    @property
    def product(self) -> ProductVariant:
        ...
    @property
    def product_precision(self) -> Precision:
        ...
    @property
    def profile(self) -> SolveProfile:
        ...
    @property
    def seconds(self) -> float:
        ...
    @property
    def steps(self) -> list[StepResult]:
        """
        StepResult per step.
        """
    @property
    def tolerance(self) -> float:
        """
        The absolute residual norm Newton stopped at.
        """
    @property
    def volume_ratio(self) -> float:
        ...
    @property
    def warnings(self) -> list[str]:
        ...
class DeformationStatistics:
    """
    Volume ratio and J range of positions.
    """
    @property
    def inverted_elements(self) -> int:
        ...
    @property
    def max_j(self) -> float:
        ...
    @property
    def min_j(self) -> float:
        ...
    @property
    def volume_ratio(self) -> float:
        ...
class ElementFields:
    """
    Per-element fields averaged over each element's quadrature points (read-only). Tensors are (m, 3, 3) indexed [element, row, column]; scalars (m,).
    """
    @property
    def cauchy(self) -> numpy.ndarray[numpy.float64]:
        """
        Cauchy stress averaged over the deformed element, (m, 3, 3); NaN where J <= 0.
        """
    @property
    def deformation_gradient(self) -> numpy.ndarray[numpy.float64]:
        """
        F, (m, 3, 3).
        """
    @property
    def energy_density(self) -> numpy.ndarray[numpy.float64]:
        """
        psi per rest volume, (m,).
        """
    @property
    def j(self) -> numpy.ndarray[numpy.float64]:
        """
        det F (deformed / rest element volume), (m,).
        """
    @property
    def min_j(self) -> numpy.ndarray[numpy.float64]:
        """
        Smallest det F over each element's points, (m,).
        """
    @property
    def pk1(self) -> numpy.ndarray[numpy.float64]:
        """
        First Piola-Kirchhoff stress P, (m, 3, 3).
        """
    @property
    def von_mises(self) -> numpy.ndarray[numpy.float64]:
        """
        von Mises stress of `cauchy`, (m,); NaN where J <= 0.
        """
class Reaction:
    """
    The force and torque a constraint set exerts on the body (read-only).
    """
    def __repr__(self) -> str:
        ...
    @property
    def about(self) -> list[float[3]]:
        """
        The torque's reference point.
        """
    @property
    def force(self) -> list[float[3]]:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def torque(self) -> list[float[3]]:
        ...
class FrameRecord:
    """
    One animation frame's solve (read-only).
    """
    @property
    def cg_iterations(self) -> int:
        ...
    @property
    def converged(self) -> bool:
        ...
    @property
    def frame(self) -> int:
        ...
    @property
    def history(self) -> list[NewtonIteration]:
        ...
    @property
    def inverted_elements(self) -> int:
        ...
    @property
    def min_j(self) -> float:
        ...
    @property
    def newton_iterations(self) -> int:
        ...
    @property
    def profile(self) -> SolveProfile:
        ...
    @property
    def reactions(self) -> list[Reaction]:
        """
        Reaction per constraint set at the frame's end.
        """
    @property
    def residual_norm(self) -> float:
        ...
    @property
    def seconds(self) -> float:
        ...
    @property
    def status(self) -> StepStatus:
        """
        The last load step's status.
        """
    @property
    def time(self) -> float:
        ...
    @property
    def volume_ratio(self) -> float:
        ...
    @property
    def warnings(self) -> list[str]:
        """
        Damage the frame shows (empty: a clean frame).
        """
class RigidTransform:
    """
    x = rotation (X - center) + center + translation; rotation a (3, 3) matrix.
    """
    @staticmethod
    def identity() -> RigidTransform:
        """
        The identity.
        """
    @staticmethod
    def rotation_about(axis: list[float[3]], angle: float, center: list[float[3]] = [0.0, 0.0, 0.0]) -> RigidTransform:
        """
        Rotation by angle (radians) about the unit axis through center.
        """
    @staticmethod
    def translation_by(offset: list[float[3]]) -> RigidTransform:
        """
        A translation.
        """
    def __init__(self, rotation: typing.Any = None, translation: typing.Any = None, center: typing.Any = None) -> None:
        """
        Identity unless given: rotation (3, 3), translation (3,), center (3,).
        """
    def __repr__(self) -> str:
        ...
    def apply(self, points: typing.Any) -> numpy.ndarray[numpy.float64]:
        """
        The map applied to a point (3,) or points (n, 3).
        """
    @property
    def center(self) -> list[float[3]]:
        """
        Rotation centre (3,).
        """
    @center.setter
    def center(self, arg1: typing.Any) -> None:
        ...
    @property
    def rotation(self) -> numpy.ndarray[numpy.float64]:
        """
        The rotation, float64 (3, 3) [row, column].
        """
    @rotation.setter
    def rotation(self, arg1: typing.Any) -> None:
        ...
    @property
    def translation(self) -> list[float[3]]:
        """
        Translation (3,).
        """
    @translation.setter
    def translation(self, arg1: typing.Any) -> None:
        ...
class ConstraintSet:
    """
    Vertices whose positions are prescribed: at rest, or moved by motion(t) -> RigidTransform at load parameter t in (0, 1], or placed by targets(t) -> (k, 3).
    """
    def __init__(self, name: str, vertices: typing.Any, motion: typing.Any = None, components: list[bool[3]] = [True, True, True], targets: typing.Any = None) -> None:
        """
        A named set of vertex indices; components says which of x, y, z it prescribes.
        """
    def __repr__(self) -> str:
        ...
    @property
    def components(self) -> list[bool[3]]:
        """
        Which of x, y, z are prescribed.
        """
    @components.setter
    def components(self, arg0: list[bool[3]]) -> None:
        ...
    @property
    def motion(self) -> typing.Any:
        """
        Callable t -> RigidTransform, or None (the set stays at rest).
        """
    @motion.setter
    def motion(self, arg1: typing.Any) -> None:
        ...
    @property
    def name(self) -> str:
        """
        Set name (used by Simulation.set_transform).
        """
    @name.setter
    def name(self, arg0: str) -> None:
        ...
    @property
    def vertices(self) -> numpy.ndarray[numpy.int32]:
        """
        Vertex indices, int32 (k,).
        """
    @vertices.setter
    def vertices(self, arg1: typing.Any) -> None:
        ...
class DynamicsOptions:
    """
    Implicit Euler time stepping.
    """
    def __init__(self, **kwargs) -> None:
        """
        Keyword arguments set the fields (time_step, density, damping_mass, damping_stiffness, substeps).
        """
    @property
    def damping_mass(self) -> float:
        """
        Rayleigh mass damping a, 1/s.
        """
    @damping_mass.setter
    def damping_mass(self, arg1: float) -> None:
        ...
    @property
    def damping_stiffness(self) -> float:
        """
        Rayleigh stiffness damping b, s.
        """
    @damping_stiffness.setter
    def damping_stiffness(self, arg1: float) -> None:
        ...
    @property
    def density(self) -> float:
        """
        Mass per rest volume (> 0).
        """
    @density.setter
    def density(self, arg0: float) -> None:
        ...
    @property
    def substeps(self) -> int:
        """
        Backward Euler steps per time step (>= 1).
        """
    @substeps.setter
    def substeps(self, arg0: int) -> None:
        ...
    @property
    def time_step(self) -> float:
        """
        Seconds per time step (> 0).
        """
    @time_step.setter
    def time_step(self, arg0: float) -> None:
        ...
class Obstacle:
    """
    A kinematic plane, sphere or cylinder the body cannot enter.
    """
    @staticmethod
    def cylinder(point: list[float[3]], axis: list[float[3]], radius: float, motion: typing.Any = None, friction: float | None = None) -> Obstacle:
        """
        An infinite cylinder about the axis through point.
        """
    @staticmethod
    def plane(point: list[float[3]], normal: list[float[3]], motion: typing.Any = None, friction: float | None = None) -> Obstacle:
        """
        A plane through point; normal points to the free side.
        """
    @staticmethod
    def sphere(center: list[float[3]], radius: float, motion: typing.Any = None, friction: float | None = None) -> Obstacle:
        """
        A sphere.
        """
    def __init__(self, **kwargs) -> None:
        """
        Keyword arguments set the fields.
        """
    @property
    def direction(self) -> list[float[3]]:
        """
        Plane normal or cylinder axis.
        """
    @direction.setter
    def direction(self, arg0: list[float[3]]) -> None:
        ...
    @property
    def friction(self) -> float | None:
        """
        Coulomb coefficient, or None for ContactOptions'.
        """
    @friction.setter
    def friction(self, arg0: float | None) -> None:
        ...
    @property
    def motion(self) -> typing.Any:
        """
        Callable t -> RigidTransform, or None.
        """
    @motion.setter
    def motion(self, arg1: typing.Any) -> None:
        ...
    @property
    def point(self) -> list[float[3]]:
        """
        Plane point, sphere centre or point on the axis.
        """
    @point.setter
    def point(self, arg0: list[float[3]]) -> None:
        ...
    @property
    def radius(self) -> float:
        """
        Sphere or cylinder radius.
        """
    @radius.setter
    def radius(self, arg0: float) -> None:
        ...
    @property
    def type(self) -> ObstacleType:
        """
        ObstacleType.
        """
    @type.setter
    def type(self, arg0: ObstacleType) -> None:
        ...
class ContactOptions:
    """
    Penalty contact with obstacles and self-contact.
    """
    def __init__(self, **kwargs) -> None:
        """
        Keyword arguments set the fields.
        """
    @property
    def friction(self) -> float:
        """
        Default Coulomb coefficient.
        """
    @friction.setter
    def friction(self, arg0: float) -> None:
        ...
    @property
    def friction_slip(self) -> float | None:
        """
        Stick-slip length; None: 1% of the vertex spacing.
        """
    @friction_slip.setter
    def friction_slip(self, arg0: float | None) -> None:
        ...
    @property
    def self(self) -> bool:
        """
        Self-collision penalty on.
        """
    @self.setter
    def self(self, arg0: bool) -> None:
        ...
    @property
    def self_stiffness(self) -> float | None:
        """
        Penalty self-contact's; None: stiffness.
        """
    @self_stiffness.setter
    def self_stiffness(self, arg0: float | None) -> None:
        ...
    @property
    def stiffness(self) -> float:
        """
        Penalty stiffness per vertex (force/length).
        """
    @stiffness.setter
    def stiffness(self, arg0: float) -> None:
        ...
    @property
    def thickness(self) -> float:
        """
        Contact layer thickness.
        """
    @thickness.setter
    def thickness(self, arg0: float) -> None:
        ...
class SolveOptions:
    """
    What a solve does. Enum fields also take their names, e.g. precision='float'.
    """
    absolute_tolerance: float
    fallback_to_double: bool
    forcing_gamma: float
    forcing_max: float
    line_search_halvings: int
    max_cg_iterations: int
    max_newton_iterations: int
    relative_tolerance: float
    def __init__(self, **kwargs) -> None:
        """
        Keyword arguments set the fields of the same names.
        """
    @property
    def body_force(self) -> list[float[3]]:
        """
        Body force per rest volume (3,).
        """
    @body_force.setter
    def body_force(self, arg1: typing.Any) -> None:
        ...
    @property
    def contact(self) -> ContactOptions:
        """
        ContactOptions (its fields can be set in place).
        """
    @contact.setter
    def contact(self, arg0: ContactOptions) -> None:
        ...
    @property
    def device(self) -> str:
        """
        Case-insensitive substring of '<platform> / <device>'; '' for SNH_DEVICE, else the first GPU.
        """
    @device.setter
    def device(self, arg1: str) -> None:
        ...
    @property
    def dynamics(self) -> DynamicsOptions | None:
        """
        DynamicsOptions, or None for quasistatics.
        """
    @dynamics.setter
    def dynamics(self, arg0: DynamicsOptions | None) -> None:
        ...
    @property
    def external_force(self) -> typing.Any:
        """
        Lumped force (n, 3) float64, or None.
        """
    @external_force.setter
    def external_force(self, arg1: typing.Any) -> None:
        ...
    @property
    def fail_on_inverted(self) -> bool:
        """
        A step ending with inverted elements fails (StepStatus.inverted_elements); later steps not run.
        """
    @fail_on_inverted.setter
    def fail_on_inverted(self, arg0: bool) -> None:
        ...
    @property
    def hessian(self) -> HessianMode:
        """
        HessianMode (or 'projected', 'adaptive').
        """
    @hessian.setter
    def hessian(self, arg1: typing.Any) -> None:
        ...
    @property
    def initial_positions(self) -> typing.Any:
        """
        Starting positions (n, 3), or None for rest.
        """
    @initial_positions.setter
    def initial_positions(self, arg1: typing.Any) -> None:
        ...
    @property
    def initial_velocities(self) -> typing.Any:
        """
        Starting velocities (n, 3) with dynamics, or None for zero.
        """
    @initial_velocities.setter
    def initial_velocities(self, arg1: typing.Any) -> None:
        ...
    @property
    def load_steps(self) -> int:
        """
        Load (or time) steps per solve.
        """
    @load_steps.setter
    def load_steps(self, arg0: int) -> None:
        ...
    @property
    def obstacles(self) -> list[Obstacle]:
        """
        Obstacle list (a copy: assign a new list).
        """
    @obstacles.setter
    def obstacles(self, arg0: list[Obstacle]) -> None:
        ...
    @property
    def precision(self) -> Precision:
        """
        Precision.double (default) or Precision.single ('double', 'float').
        """
    @precision.setter
    def precision(self, arg1: typing.Any) -> None:
        ...
    @property
    def preconditioner(self) -> Preconditioner | None:
        """
        Preconditioner (or 'none', 'block-jacobi', 'multigrid'), or None ('automatic'): the measured choice.
        """
    @preconditioner.setter
    def preconditioner(self, arg1: typing.Any) -> None:
        ...
    @property
    def product(self) -> ProductVariant | None:
        """
        ProductVariant (or its name), or None ('automatic'): the measured choice.
        """
    @product.setter
    def product(self, arg1: typing.Any) -> None:
        ...
    @property
    def product_precision(self) -> Precision | None:
        """
        Precision of CG's products in double solves, or None (float).
        """
    @product_precision.setter
    def product_precision(self, arg1: typing.Any) -> None:
        ...
    @property
    def ramp_loads(self) -> bool:
        """
        Forces grow with the load steps.
        """
    @ramp_loads.setter
    def ramp_loads(self, arg0: bool) -> None:
        ...
    @property
    def strain_tolerance(self) -> float | None:
        """
        None: 1e-6 double, 1e-4 float.
        """
    @strain_tolerance.setter
    def strain_tolerance(self, arg0: float | None) -> None:
        ...
class ResolvedSetting:
    """
    One resolved setting: its name, value and reason.
    """
    def __repr__(self) -> str:
        ...
    @property
    def name(self) -> str:
        """
        The option's name (as in scene files).
        """
    @property
    def reason(self) -> str:
        """
        'given', 'default', or the rule that chose it.
        """
    @property
    def value(self) -> str:
        """
        Its value as printed.
        """
class ResolvedConfiguration:
    """
    The options with every automatic choice made, each with its reason (read-only).
    """
    def as_dict(self) -> dict:
        """
        {name: (value, reason)} in order.
        """
    def setting(self, name: str) -> ResolvedSetting:
        """
        The setting named `name`; raises snh.Error when there is none.
        """
    @property
    def absolute_tolerance(self) -> float:
        """
        The stopping test's absolute part.
        """
    @property
    def barrier_stiffness(self) -> float:
        """
        Barrier self-contact's kappa (0 without the barrier).
        """
    @property
    def options(self) -> SolveOptions:
        """
        The resolved SolveOptions.
        """
    @property
    def relative_tolerance(self) -> float:
        """
        The stopping test's relative part.
        """
    @property
    def settings(self) -> list[ResolvedSetting]:
        """
        Every setting, in a fixed order.
        """
class SimulationState:
    """
    A simulation's full state (Simulation.checkpoint), to restore or to write with write_checkpoint.
    """
    @property
    def positions(self) -> numpy.ndarray[numpy.float64]:
        """
        float64 (n, 3).
        """
    @property
    def time(self) -> float:
        """
        Simulated time.
        """
    @property
    def velocities(self) -> numpy.ndarray[numpy.float64]:
        """
        float64 (n, 3); empty without dynamics.
        """
class Simulation:
    """
    A simulation driven frame by frame: built once (kernels compiled, mesh uploaded), then solved from its current state after new targets and loads.
    """
    @typing.overload
    def __init__(self, mesh: Mesh, materials: MaterialMap, constraints: list[ConstraintSet] = [], options: SolveOptions | None = None) -> None:
        """
        With a MaterialMap (one material per element).
        """
    @typing.overload
    def __init__(self, mesh: Mesh, material: Material, constraints: list[ConstraintSet] = [], options: SolveOptions | None = None) -> None:
        """
        Validates everything (snh.Error naming the input), builds the kernels and uploads the mesh.
        """
    def checkpoint(self) -> SimulationState:
        """
        The full state (SimulationState): positions, velocities, time, friction anchors, constraint targets and loads. The next solve rebuilds the preconditioner, as after restore, so that both continue identically.
        """
    def fields(self) -> ElementFields:
        """
        Per-element F, J, stresses and energy density (ElementFields).
        """
    def reactions(self) -> list[Reaction]:
        """
        Per constraint set, the force and torque it exerts on the body (Reaction list).
        """
    def restart(self) -> None:
        """
        Back to the initial state, callbacks and no force.
        """
    def restore(self, state: SimulationState) -> None:
        """
        Replaces the state by a checkpoint of a simulation built from the same mesh, materials, constraint sets and options; the solves that follow give bitwise the results the original gave.
        """
    def set_body_force(self, force_per_rest_volume: typing.Any) -> None:
        """
        Body force per rest volume (3,).
        """
    def set_external_force(self, force: typing.Any) -> None:
        """
        Lumped force (n, 3), or None for none.
        """
    def set_positions(self, set: str, positions: typing.Any) -> None:
        """
        Absolute target positions (k, 3) of the set's vertices.
        """
    def set_state(self, positions: typing.Any) -> None:
        """
        Replaces the state (n, 3).
        """
    def set_transform(self, set: str, transform: RigidTransform) -> None:
        """
        The set's absolute target transform for the next solve.
        """
    def set_velocities(self, velocities: typing.Any) -> None:
        """
        With dynamics: replaces the velocities (n, 3), or None for zero.
        """
    def solve(self, load_steps: int = 0, progress: typing.Any = None, on_step: typing.Any = None) -> SolveResult:
        """
        Moves the constrained vertices to their targets in load_steps (0: the options') and brings the body to equilibrium. progress(NewtonIteration) is called after each Newton update: return False to cancel (SolveResult.cancelled). on_step(step, positions) is called after each step. Exceptions raised in either propagate. Runs without the GIL.
        """
    @property
    def applied_force(self) -> numpy.ndarray[numpy.float64]:
        """
        The lumped external force of the last solve's final step, (n, 3).
        """
    @property
    def configuration(self) -> ResolvedConfiguration:
        """
        The ResolvedConfiguration: every automatic choice made, with its reason.
        """
    @property
    def constraints(self) -> list[ConstraintSet]:
        """
        The constraint sets (copies).
        """
    @property
    def device(self) -> DeviceInfo:
        """
        The OpenCL device (DeviceInfo).
        """
    @property
    def materials(self) -> MaterialMap:
        """
        The MaterialMap (a copy).
        """
    @property
    def mesh(self) -> Mesh:
        """
        The mesh (a copy).
        """
    @property
    def positions(self) -> numpy.ndarray[numpy.float64]:
        """
        Current positions, float64 (n, 3).
        """
    @property
    def time(self) -> float:
        """
        With dynamics: simulated time.
        """
    @property
    def tolerance(self) -> float:
        """
        The absolute residual tolerance.
        """
    @property
    def velocities(self) -> numpy.ndarray[numpy.float64]:
        """
        With dynamics: velocities, float64 (n, 3).
        """
class SceneProgress:
    """
    A scene run's progress after a step or frame (read-only).
    """
    @property
    def cg_iterations(self) -> int:
        ...
    @property
    def count(self) -> int:
        ...
    @property
    def frame(self) -> bool:
        """
        True for a rig's frame, False for a load step.
        """
    @property
    def index(self) -> int:
        """
        1-based.
        """
    @property
    def min_j(self) -> float:
        ...
    @property
    def newton_iterations(self) -> int:
        ...
    @property
    def residual_norm(self) -> float:
        ...
    @property
    def seconds(self) -> float:
        ...
    @property
    def status(self) -> StepStatus:
        ...
    @property
    def time(self) -> float:
        ...
class SceneStep:
    """
    What a scene run measured after a step or frame (read-only).
    """
    @property
    def max_self_penetration(self) -> float:
        ...
    @property
    def min_j(self) -> float:
        ...
    @property
    def reactions(self) -> list[Reaction] | None:
        """
        Reaction list, or None.
        """
    @property
    def rigid_fit_rms(self) -> float:
        ...
    @property
    def rigid_fit_rms_relative(self) -> float:
        ...
    @property
    def self_contact_measured(self) -> bool:
        ...
    @property
    def shape_defined(self) -> bool:
        """
        Whether the shape was measured.
        """
    @property
    def unresolved_self_contacts(self) -> int:
        ...
    @property
    def volume_ratio(self) -> float:
        ...
class SceneRun:
    """
    A scene run's outcome (read-only).
    """
    @property
    def converged(self) -> bool:
        """
        Every step or frame converged.
        """
    @property
    def device(self) -> DeviceInfo:
        ...
    @property
    def frames(self) -> list[FrameRecord]:
        """
        FrameRecord per frame of a rig.
        """
    @property
    def options(self) -> SolveOptions:
        """
        The SolveOptions as run.
        """
    @property
    def resolved(self) -> ResolvedConfiguration:
        """
        The ResolvedConfiguration it ran with.
        """
    @property
    def result(self) -> SolveResult:
        """
        The SolveResult (load or time steps).
        """
    @property
    def steps(self) -> list[SceneStep]:
        """
        SceneStep per step or frame.
        """
    @property
    def warnings(self) -> list[str]:
        ...
class TriangleSurface:
    """
    A triangle surface: positions (n, 3), triangles (t, 3).
    """
    def __init__(self, positions: typing.Any, triangles: typing.Any) -> None:
        """
        From positions (n, 3) and triangles (t, 3).
        """
    @property
    def positions(self) -> numpy.ndarray[numpy.float64]:
        """
        float64 (n, 3).
        """
    @property
    def triangle_count(self) -> int:
        ...
    @property
    def triangles(self) -> numpy.ndarray[numpy.int32]:
        """
        int32 (t, 3), outward by the right-hand rule.
        """
    @property
    def vertex_count(self) -> int:
        ...
class VoxelizeOptions:
    """
    Voxelizer settings.
    """
    def __init__(self, **kwargs) -> None:
        ...
    @property
    def cover_surface(self) -> bool:
        """
        Also keep cells the surface crosses.
        """
    @cover_surface.setter
    def cover_surface(self, arg0: bool) -> None:
        ...
    @property
    def max_grid_cells(self) -> int:
        """
        Refuse larger grids.
        """
    @max_grid_cells.setter
    def max_grid_cells(self, arg0: int) -> None:
        ...
    @property
    def name(self) -> str:
        """
        The surface's file, for errors and warnings.
        """
    @name.setter
    def name(self, arg0: str) -> None:
        ...
    @property
    def strict(self) -> bool:
        """
        Refuse surfaces that are not closed; inside by crossing counts.
        """
    @strict.setter
    def strict(self, arg0: bool) -> None:
        ...
    @property
    def weld_tolerance(self) -> float:
        """
        Weld vertices closer than this times the bounding box's diagonal.
        """
    @weld_tolerance.setter
    def weld_tolerance(self, arg0: float) -> None:
        ...
    @property
    def winding_beta(self) -> float:
        """
        Accuracy of the fast winding number.
        """
    @winding_beta.setter
    def winding_beta(self, arg0: float) -> None:
        ...
class Voxelization:
    """
    A hex8 lattice covering a closed surface's interior.
    """
    @property
    def cell(self) -> float:
        """
        Cube side.
        """
    @property
    def components(self) -> int:
        """
        Connected pieces.
        """
    @property
    def dims(self) -> list[int[3]]:
        """
        Grid cells per axis.
        """
    @property
    def element_cell(self) -> numpy.ndarray[numpy.int32]:
        """
        Grid cell (i, j, k) per element, int32 (m, 3).
        """
    @property
    def lattice(self) -> Mesh:
        """
        The hex8 Mesh.
        """
    @property
    def origin(self) -> list[float[3]]:
        """
        Corner of grid cell (0, 0, 0).
        """
    @property
    def warnings(self) -> list[str]:
        """
        The surface's defects, one line per class.
        """
class Embedding:
    """
    Each surface vertex's element and trilinear weights.
    """
    @property
    def element(self) -> numpy.ndarray[numpy.int32]:
        """
        int32 (k,).
        """
    @property
    def weights(self) -> numpy.ndarray[numpy.float64]:
        """
        float64 (k, 8).
        """
class Capsule:
    """
    Points within radius of the segment a-b.
    """
    a: list[float[3]]
    b: list[float[3]]
    radius: float
    def __init__(self, a: list[float[3]], b: list[float[3]], radius: float) -> None:
        ...
class Bone:
    """
    A named solid (Capsule or closed TriangleSurface) whose vertices move with it.
    """
    name: str
    shape: Capsule | TriangleSurface
    def __init__(self, name: str, shape: Capsule | TriangleSurface) -> None:
        ...
class Animation:
    """
    Per frame, a 4x4 transform for each animated bone.
    """
    def __init__(self, bones: list[str], times: typing.Any, transforms: typing.Any) -> None:
        """
        bones: names; times: (frames,); transforms: (frames, bones, 4, 4).
        """
    @property
    def bones(self) -> list[str]:
        """
        Animated bone names.
        """
    @property
    def frame_count(self) -> int:
        ...
    @property
    def times(self) -> list[float]:
        """
        Per-frame times.
        """
    @property
    def transforms(self) -> numpy.ndarray[numpy.float64]:
        """
        float64 (frames, bones, 4, 4), row-major matrices.
        """
class FrameOptions:
    """
    Frame driver settings.
    """
    def __init__(self, **kwargs) -> None:
        ...
    @property
    def fail_on_inverted(self) -> bool:
        """
        A frame ending with inverted elements fails (StepStatus.inverted_elements) and is the last.
        """
    @fail_on_inverted.setter
    def fail_on_inverted(self, arg0: bool) -> None:
        ...
    @property
    def load_steps(self) -> int:
        """
        Load steps per frame.
        """
    @load_steps.setter
    def load_steps(self, arg0: int) -> None:
        ...
    @property
    def stop_on_failure(self) -> bool:
        """
        Stop at the first failed frame.
        """
    @stop_on_failure.setter
    def stop_on_failure(self, arg0: bool) -> None:
        ...
class WeightPolicy:
    """
    What read_character does with skin weights that do not sum to 1: normalize divides them by their sum (one warning), strict refuses the file naming the vertex.
    
    Members:
    
      normalize
    
      strict
    """
    __members__: typing.ClassVar[dict[str, WeightPolicy]]
    normalize: typing.ClassVar[WeightPolicy]
    strict: typing.ClassVar[WeightPolicy]
    def __eq__(self, other: typing.Any) -> bool:
        ...
    def __getstate__(self) -> int:
        ...
    def __hash__(self) -> int:
        ...
    def __index__(self) -> int:
        ...
    def __init__(self, value: int) -> None:
        ...
    def __int__(self) -> int:
        ...
    def __ne__(self, other: typing.Any) -> bool:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, state: int) -> None:
        ...
    def __str__(self) -> str:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def value(self) -> int:
        ...
class CharacterReadOptions:
    """
    What read_character reads.
    """
    def __init__(self, **kwargs) -> None:
        """
        Keyword arguments set the fields of the same names.
        """
    @property
    def clip(self) -> str:
        """
        The clip by name ('': by clip_index, else the first).
        """
    @clip.setter
    def clip(self, arg0: str) -> None:
        ...
    @property
    def clip_index(self) -> int | None:
        """
        The clip by index among the file's (>= 0), or None.
        """
    @clip_index.setter
    def clip_index(self, arg0: int | None) -> None:
        ...
    @property
    def first_frame(self) -> int:
        """
        First frame sampled (time frame / fps).
        """
    @first_frame.setter
    def first_frame(self, arg0: int) -> None:
        ...
    @property
    def fps(self) -> float:
        """
        Frames per second the clip is sampled at.
        """
    @fps.setter
    def fps(self, arg0: float) -> None:
        ...
    @property
    def last_frame(self) -> int | None:
        """
        Last frame sampled (inclusive); None: up to the clip's last key.
        """
    @last_frame.setter
    def last_frame(self, arg0: int | None) -> None:
        ...
    @property
    def require_clip(self) -> bool:
        """
        False: a file without animation reads as a character without a clip.
        """
    @require_clip.setter
    def require_clip(self, arg0: bool) -> None:
        ...
    @property
    def weight_tolerance(self) -> float:
        """
        Sums within this of 1 are taken as they are.
        """
    @weight_tolerance.setter
    def weight_tolerance(self, arg0: float) -> None:
        ...
    @property
    def weights(self) -> WeightPolicy:
        """
        WeightPolicy for sums off 1.
        """
    @weights.setter
    def weights(self, arg0: WeightPolicy) -> None:
        ...
    @property
    def weld_distance(self) -> float | None:
        """
        Positions closer than this are welded (None: 1e-9 of the bounding box's diagonal).
        """
    @weld_distance.setter
    def weld_distance(self, arg0: float | None) -> None:
        ...
class Joint:
    """
    A joint of the skeleton: a node that skins vertices (read-only).
    """
    def __repr__(self) -> str:
        ...
    @property
    def inverse_bind(self) -> numpy.ndarray[numpy.float64]:
        """
        Rest (mesh) space to joint space, float64 (4, 4) [row, column].
        """
    @property
    def name(self) -> str:
        ...
    @property
    def parent(self) -> int:
        """
        The nearest ancestor that is a joint, or -1.
        """
    @property
    def rest_position(self) -> list[float[3]]:
        """
        The joint's origin at rest.
        """
class SkinWeights:
    """
    Skin weights per vertex in compressed rows: vertex v's joints are joint[offset[v]:offset[v + 1]] with weight[...].
    """
    def __init__(self, offset: typing.Any, joint: typing.Any, weight: typing.Any) -> None:
        """
        From offset (vertices + 1,), joint (k,) and weight (k,).
        """
    @property
    def joint(self) -> numpy.ndarray[numpy.int32]:
        """
        int32 (k,).
        """
    @property
    def offset(self) -> numpy.ndarray[numpy.int32]:
        """
        int32 (vertices + 1,).
        """
    @property
    def vertex_count(self) -> int:
        ...
    @property
    def weight(self) -> numpy.ndarray[numpy.float64]:
        """
        float64 (k,).
        """
class CharacterClip:
    """
    A clip sampled at fps (read-only).
    """
    @property
    def first_frame(self) -> int:
        ...
    @property
    def fps(self) -> float:
        ...
    @property
    def frame_count(self) -> int:
        ...
    @property
    def index(self) -> int:
        """
        Among the file's clips.
        """
    @property
    def name(self) -> str:
        ...
    @property
    def skinning(self) -> numpy.ndarray[numpy.float64]:
        """
        Per frame and joint, world(t) * inverse_bind (rest point to posed point), float64 (frames, joints, 4, 4).
        """
    @property
    def times(self) -> numpy.ndarray[numpy.float64]:
        """
        Seconds per frame (frame / fps), float64 (frames,).
        """
class Character:
    """
    A skinned character as read_character reads it (read-only).
    """
    def __repr__(self) -> str:
        ...
    @property
    def clip(self) -> CharacterClip:
        """
        The sampled CharacterClip (empty without one).
        """
    @property
    def clip_names(self) -> list[str]:
        """
        The file's clips.
        """
    @property
    def file(self) -> str:
        ...
    @property
    def has_clip(self) -> bool:
        ...
    @property
    def joints(self) -> list[Joint]:
        """
        Joint list, parents before children.
        """
    @property
    def surface(self) -> TriangleSurface:
        """
        The skin as the file gives it (seams kept): the output's vertex order.
        """
    @property
    def warnings(self) -> list[str]:
        """
        What was repaired on reading, one line per kind.
        """
    @property
    def weights(self) -> SkinWeights:
        """
        SkinWeights per surface vertex.
        """
    @property
    def welded(self) -> TriangleSurface:
        """
        The skin with coincident positions welded (voxelized).
        """
    @property
    def welded_index(self) -> numpy.ndarray[numpy.int32]:
        """
        Each surface vertex's welded vertex, int32 (n,).
        """
class CharacterBoneOptions:
    """
    How bones are made from the skeleton.
    """
    def __init__(self, **kwargs) -> None:
        """
        Keyword arguments set the fields of the same names.
        """
    @property
    def exclude(self) -> list[str]:
        """
        Joints without a bone, by name or glob pattern (a copy: assign a new list).
        """
    @exclude.setter
    def exclude(self, arg0: list[str]) -> None:
        ...
    @property
    def joint_clearance(self) -> float:
        """
        Flesh left free at each end, as a fraction of the segment's length; < 0: joint to joint.
        """
    @joint_clearance.setter
    def joint_clearance(self, arg0: float) -> None:
        ...
    @property
    def leaf_fraction(self) -> float:
        """
        A leaf joint's segment as a fraction of its parent's; 0: from the skin (leaf_from_skin) or none.
        """
    @leaf_fraction.setter
    def leaf_fraction(self, arg0: float) -> None:
        ...
    @property
    def leaf_from_skin(self) -> bool:
        """
        With leaf_fraction 0, a leaf's segment reaches 3/4 of the way to the farthest skin it weighs most.
        """
    @leaf_from_skin.setter
    def leaf_from_skin(self, arg0: bool) -> None:
        ...
    @property
    def radius(self) -> dict[str, float]:
        """
        {joint: absolute radius} (a copy: assign a new dict).
        """
    @radius.setter
    def radius(self, arg0: dict[str, float]) -> None:
        ...
    @property
    def radius_fraction(self) -> float:
        """
        A bone's radius as a fraction of its segment's distance from the skin.
        """
    @radius_fraction.setter
    def radius_fraction(self, arg0: float) -> None:
        ...
    @property
    def touching_radius(self) -> float:
        """
        Radius of a bone whose segment touches the skin (absolute); 0 leaves such bones out.
        """
    @touching_radius.setter
    def touching_radius(self, arg0: float) -> None:
        ...
class CharacterBones:
    """
    Bones from the skeleton and their animation (read-only).
    """
    @property
    def animation(self) -> Animation:
        """
        Every bone's skinning matrix per frame.
        """
    @property
    def bones(self) -> list[Bone]:
        """
        Bone list, named as their joints.
        """
    @property
    def joint(self) -> numpy.ndarray[numpy.int32]:
        """
        Each bone's joint, int32.
        """
    @property
    def warnings(self) -> list[str]:
        """
        Bones given the floor radius or left out.
        """
class CharacterPrepareOptions:
    """
    How prepare_character rigs a character.
    """
    def __init__(self, **kwargs) -> None:
        """
        Keyword arguments set the fields of the same names.
        """
    @property
    def bones(self) -> CharacterBoneOptions:
        """
        CharacterBoneOptions (its fields can be set in place).
        """
    @bones.setter
    def bones(self, arg0: CharacterBoneOptions) -> None:
        ...
    @property
    def max_outside_fraction(self) -> float:
        """
        A surface vertex farther than this fraction of the diagonal from every element is an error.
        """
    @max_outside_fraction.setter
    def max_outside_fraction(self, arg0: float) -> None:
        ...
    @property
    def pieces(self) -> str:
        """
        Lattice pieces no bone holds: 'attach' (default), 'drop' or 'error'.
        """
    @pieces.setter
    def pieces(self, arg1: str) -> None:
        ...
    @property
    def touching_radius_cells(self) -> float:
        """
        Cells of radius for a bone touching the skin, unless bones.touching_radius is set.
        """
    @touching_radius_cells.setter
    def touching_radius_cells(self, arg0: float) -> None:
        ...
    @property
    def voxelize(self) -> VoxelizeOptions:
        """
        VoxelizeOptions (its fields can be set in place).
        """
    @voxelize.setter
    def voxelize(self, arg0: VoxelizeOptions) -> None:
        ...
class CharacterRig:
    """
    What a character's simulation needs (read-only).
    """
    @property
    def bones(self) -> CharacterBones:
        """
        CharacterBones.
        """
    @property
    def cell(self) -> float:
        """
        The lattice's cube side.
        """
    @property
    def constraints(self) -> list[ConstraintSet]:
        """
        One ConstraintSet per bone.
        """
    @property
    def embedding(self) -> Embedding:
        """
        Embedding of every surface vertex (file order).
        """
    @property
    def lattice_weights(self) -> SkinWeights:
        """
        SkinWeights per lattice vertex, for the skinned guess.
        """
    @property
    def max_outside_distance(self) -> float:
        """
        The largest distance of those from their element.
        """
    @property
    def vertices_outside(self) -> int:
        """
        Surface vertices outside every element (they follow the nearest one).
        """
    @property
    def voxels(self) -> Voxelization:
        """
        The welded surface's Voxelization.
        """
    @property
    def warnings(self) -> list[str]:
        """
        What was repaired, one line per kind.
        """
class SkinDeviation:
    """
    How far a frame's simulated surface is from the linear-blend-skinned one.
    """
    @property
    def max_distance(self) -> float:
        ...
    @property
    def mean_distance(self) -> float:
        ...
class CharacterFrame:
    """
    One frame of a character (read-only).
    """
    @property
    def lbs(self) -> SkinDeviation:
        """
        SkinDeviation from linear blend skinning.
        """
    @property
    def record(self) -> FrameRecord:
        """
        The FrameRecord, frame and time as in the clip.
        """
class CharacterFrameOptions:
    """
    How run_character_frames runs the frames.
    """
    def __init__(self, **kwargs) -> None:
        """
        Keyword arguments set the fields of the same names.
        """
    @property
    def frames(self) -> FrameOptions:
        """
        FrameOptions (its fields can be set in place).
        """
    @frames.setter
    def frames(self, arg0: FrameOptions) -> None:
        ...
    @property
    def skinned_guess(self) -> bool:
        """
        Start each frame from the last state moved by the lattice skinning's change.
        """
    @skinned_guess.setter
    def skinned_guess(self, arg0: bool) -> None:
        ...
class PointCache:
    """
    The same points sampled over frames (PC2, MDD).
    """
    def __init__(self, **kwargs) -> None:
        """
        Keyword arguments set the fields (samples, start_frame, sample_rate, times, point_count).
        """
    @property
    def point_count(self) -> int:
        """
        Points per sample (set by samples).
        """
    @point_count.setter
    def point_count(self, arg0: int) -> None:
        ...
    @property
    def sample_count(self) -> int:
        """
        Samples held.
        """
    @property
    def sample_rate(self) -> float:
        """
        PC2: frames between samples.
        """
    @sample_rate.setter
    def sample_rate(self, arg0: float) -> None:
        ...
    @property
    def samples(self) -> numpy.ndarray[numpy.float32]:
        """
        float32 (samples, points, 3); setting it sets point_count.
        """
    @samples.setter
    def samples(self, arg1: typing.Any) -> None:
        ...
    @property
    def start_frame(self) -> float:
        """
        PC2: the first sample's frame.
        """
    @start_frame.setter
    def start_frame(self, arg0: float) -> None:
        ...
    @property
    def times(self) -> numpy.ndarray[numpy.float64]:
        """
        MDD: seconds per sample, float64 (samples,).
        """
    @times.setter
    def times(self, arg1: typing.Any) -> None:
        ...
class CharacterCacheSeries:
    """
    Collects a character's frames and writes its point caches.
    """
    def __init__(self, character: Character, pc2: str = '', mdd: str = '', lbs: str = '') -> None:
        """
        The simulated surface to pc2 and/or mdd, the skinned one to lbs (.pc2 or .mdd); '' skips.
        """
    def add(self, clip_frame: int, surface: typing.Any) -> None:
        """
        A frame (numbered as in the clip) with the simulated surface (n, 3).
        """
    def finish(self) -> None:
        """
        Writes the files.
        """
class SceneParameters:
    """
    Size, material and steps of a built-in scene.
    """
    barrier: Barrier | None
    poisson_ratio: float
    seed: int
    strain_tolerance: float
    youngs_modulus: float
    def __init__(self, **kwargs) -> None:
        """
        Keyword arguments set the fields of the same names.
        """
    @property
    def element_type(self) -> ElementType:
        """
        hex8 or tet4 (each hex split in six).
        """
    @element_type.setter
    def element_type(self, arg0: ElementType) -> None:
        ...
    @property
    def resolution(self) -> int | None:
        """
        Cells across; None: the scene's default.
        """
    @resolution.setter
    def resolution(self, arg0: int | None) -> None:
        ...
    @property
    def steps(self) -> int | None:
        """
        Load steps; None: the scene's default.
        """
    @steps.setter
    def steps(self, arg0: int | None) -> None:
        ...
class Scene:
    """
    A mesh, a material, constraints and solve options, ready to simulate.
    """
    description: str
    name: str
    def simulation(self, options: SolveOptions | None = None) -> Simulation:
        """
        A Simulation of the scene (options: the scene's unless given).
        """
    @property
    def constraints(self) -> list[ConstraintSet]:
        """
        ConstraintSet list (a copy: assign a new list).
        """
    @constraints.setter
    def constraints(self, arg0: list[ConstraintSet]) -> None:
        ...
    @property
    def material(self) -> StableNeoHookean:
        """
        The StableNeoHookean material.
        """
    @material.setter
    def material(self, arg0: StableNeoHookean) -> None:
        ...
    @property
    def mesh(self) -> Mesh:
        """
        The Mesh.
        """
    @mesh.setter
    def mesh(self, arg0: Mesh) -> None:
        ...
    @property
    def options(self) -> SolveOptions:
        """
        SolveOptions (fields can be set in place).
        """
    @options.setter
    def options(self, arg0: SolveOptions) -> None:
        ...
class SceneFile:
    """
    A scene file as read: the scene, its materials, rig and outputs.
    """
    @property
    def animation(self) -> typing.Any:
        """
        The rig's Animation, or None.
        """
    @property
    def bones(self) -> typing.Any:
        """
        The rig's Bone list, or None.
        """
    @property
    def embedding(self) -> typing.Any:
        """
        The surface's Embedding, or None.
        """
    @property
    def json_path(self) -> str:
        """
        Output JSON summary, or ''.
        """
    @json_path.setter
    def json_path(self, arg0: str) -> None:
        ...
    @property
    def material(self) -> Material:
        """
        The base Material.
        """
    @material.setter
    def material(self, arg0: Material) -> None:
        ...
    @property
    def materials(self) -> MaterialMap:
        """
        Every element's material (MaterialMap).
        """
    @materials.setter
    def materials(self, arg0: MaterialMap) -> None:
        ...
    @property
    def scene(self) -> Scene:
        """
        The Scene (its options are the file's).
        """
    @scene.setter
    def scene(self, arg0: Scene) -> None:
        ...
    @property
    def surface(self) -> typing.Any:
        """
        The embedded TriangleSurface, or None.
        """
    @property
    def surface_prefix(self) -> str:
        """
        Output OBJ prefix, or ''.
        """
    @surface_prefix.setter
    def surface_prefix(self, arg0: str) -> None:
        ...
    @property
    def voxels(self) -> typing.Any:
        """
        The Voxelization of the surface, or None.
        """
    @property
    def vtu_dir(self) -> str:
        """
        Output folder of the .vtu series, or ''.
        """
    @vtu_dir.setter
    def vtu_dir(self, arg0: str) -> None:
        ...
def bone_constraints(lattice: Mesh, bones: list[Bone]) -> list[ConstraintSet]:
    """
    One ConstraintSet per bone of the lattice vertices inside it (first bone wins at joints).
    """
def bone_contains(bone: Bone, point: list[float[3]]) -> bool:
    """
    Whether the rest point is inside.
    """
def boundary_surface(mesh: Mesh, positions: typing.Any = None) -> tuple:
    """
    The mesh's boundary as (TriangleSurface, vertices): outward triangles over the boundary vertices at positions (n, 3; None: rest), and the mesh vertex (int32) of each surface vertex.
    """
def character_bones(character: Character, options: CharacterBoneOptions | None = None) -> CharacterBones:
    """
    A capsule per kept joint's segment (joint to child, trimmed by joint_clearance) and its animation.
    """
def character_cell(character: Character, resolution: int) -> float:
    """
    The cube side that puts resolution cells along the longest side of the bind pose's bounding box.
    """
def compute_element_fields(mesh: Mesh, materials: MaterialMap, positions: typing.Any) -> ElementFields:
    """
    ElementFields at positions (n, 3).
    """
def deformation_statistics(mesh: Mesh, positions: typing.Any) -> DeformationStatistics:
    """
    Volume ratio, J range and inverted elements at positions (n, 3).
    """
def elastic_forces(mesh: Mesh, materials: MaterialMap, positions: typing.Any) -> numpy.ndarray[numpy.float64]:
    """
    Elastic nodal forces -dE/dx, (n, 3).
    """
def element_fields_for_vtu(fields: ElementFields, materials: MaterialMap) -> dict:
    """
    The fields as write_vtu cell_fields: {name: array}, tensors (m, 3, 3) [row, column].
    """
def elements_in_box(mesh: Mesh, lo: list[float[3]], hi: list[float[3]]) -> numpy.ndarray[numpy.int32]:
    """
    Elements whose centroid lies in the box.
    """
def elements_in_group(mesh: Mesh, group: typing.Any) -> numpy.ndarray[numpy.int32]:
    """
    The elements of the volume group with this name (str) or tag (int).
    """
def elements_in_sphere(mesh: Mesh, center: list[float[3]], radius: float) -> numpy.ndarray[numpy.int32]:
    """
    Elements whose centroid lies in the sphere.
    """
def elements_with_value(mesh: Mesh, array: str, value: float) -> numpy.ndarray[numpy.int32]:
    """
    Elements whose cell-array value equals value.
    """
def elements_with_value_in(mesh: Mesh, array: str, lo: float, hi: float) -> numpy.ndarray[numpy.int32]:
    """
    Elements whose value lies in [lo, hi].
    """
def embed(voxels: Voxelization, surface: TriangleSurface) -> Embedding:
    """
    Embeds the surface in the voxel lattice.
    """
def embedded_positions(embedding: Embedding, lattice: Mesh, positions: typing.Any) -> numpy.ndarray[numpy.float64]:
    """
    Surface positions (k, 3) for lattice positions (n, 3).
    """
def enclosed_volume(surface: TriangleSurface) -> float:
    """
    Volume by the divergence theorem.
    """
def identity_matrix4() -> numpy.ndarray[numpy.float64]:
    """
    The 4x4 identity.
    """
def linear_blend_skinning(rest: typing.Any, weights: SkinWeights, matrices: typing.Any) -> numpy.ndarray[numpy.float64]:
    """
    sum_j w_j M_j x per vertex of rest (n, 3) with one matrix (joints, 4, 4) per joint: (n, 3).
    """
def list_devices() -> list[DeviceInfo]:
    """
    Every OpenCL device on this machine (DeviceInfo list).
    """
def load_scene(path: str) -> SceneFile:
    """
    Reads a scene file (docs/scene-files.md); snh.Error names the key at fault.
    """
def lump_body_force(mesh: Mesh, force_per_rest_volume: typing.Any) -> numpy.ndarray[numpy.float64]:
    """
    Nodal forces (n, 3) of a uniform body force per rest volume.
    """
def lumped_mass(mesh: Mesh, density: float) -> numpy.ndarray[numpy.float64]:
    """
    Row-sum lumped mass per vertex (n,) of a uniform density.
    """
def make_box_lattice(nx: int, ny: int, nz: int, h: float, origin: list[float[3]] = [0.0, 0.0, 0.0]) -> Mesh:
    """
    nx * ny * nz hex8 cubes of side h from origin.
    """
def make_material_map(mesh: Mesh, base: Material, regions: list[MaterialRegion]) -> MaterialMap:
    """
    Base material plus regions (snh.Error for an empty region, an index out of range, an element in two).
    """
def make_scene(name: str, parameters: SceneParameters | None = None) -> Scene:
    """
    A built-in scene (scene_names()) with parameters (default: scene_defaults(name)).
    """
def make_tet_box(nx: int, ny: int, nz: int, h: float, origin: list[float[3]] = [0.0, 0.0, 0.0]) -> Mesh:
    """
    The box lattice with each cube split into six tet4 around its main diagonal.
    """
def make_voxel_cylinder(radius: float, length: float, h: float) -> Mesh:
    """
    The lattice cells within radius of the z axis: a voxelized hex8 cylinder.
    """
def max_poisson_ratio(materials: MaterialMap) -> float:
    """
    The largest small-strain Poisson's ratio over the materials some element uses.
    """
def parse_animation_csv(text: str, name: str = '<string>') -> Animation:
    ...
def parse_animation_json(text: str, name: str = '<string>') -> Animation:
    ...
@typing.overload
def prepare_character(character: Character, cell: float, options: CharacterPrepareOptions | None = None) -> CharacterRig:
    """
    Voxelizes the welded surface at cell, embeds every surface vertex, makes the bones and their constraint sets and carries the skin weights to the lattice.
    """
@typing.overload
def prepare_character(character: Character, cell: float, bones: CharacterBoneOptions | None = None, voxelize: VoxelizeOptions | None = None) -> CharacterRig:
    """
    The same with bone and voxelizer options alone (the other options' defaults).
    """
def read_animation(path: str) -> Animation:
    """
    Reads a .json or .csv animation.
    """
def read_character(path: str, options: CharacterReadOptions | None = None) -> Character:
    """
    Reads a skinned character (glTF 2.0, FBX, Collada): surface, joints, weights and a clip sampled at fps. snh.Error names the file and the item at fault.
    """
def read_checkpoint(path: str) -> SimulationState:
    """
    Reads a checkpoint file; snh.Error names the file and the item for a damaged one.
    """
def read_mdd(path: str) -> PointCache:
    """
    Reads an MDD point cache.
    """
def read_mesh(path: str, allow_coincident_vertices: bool = False) -> Mesh:
    """
    Reads .msh, .vtk, .vtu, .mesh, .node/.ele (tet4 or hex8) with groups and arrays; snh.Error names the file and line at fault.
    """
def read_pc2(path: str) -> PointCache:
    """
    Reads a PC2 point cache.
    """
def read_surface(path: str) -> TriangleSurface:
    """
    Reads .obj, .ply or .stl (polygons fanned).
    """
def run_character_frames(simulation: Simulation, character: Character, rig: CharacterRig, options: CharacterFrameOptions | None = None, on_frame: typing.Any = None) -> list[CharacterFrame]:
    """
    Runs the clip's frames on a Simulation of rig.voxels.lattice with rig.constraints. on_frame(frame, lattice (n, 3), surface (k, 3), skinned (k, 3)) after each frame; returning False stops (None goes on); an exception raised in it propagates. Runs without the GIL. Returns CharacterFrames.
    """
def run_frames(simulation: Simulation, animation: Animation, embedding: Embedding = None, options: FrameOptions | None = None, on_frame: typing.Any = None) -> list[FrameRecord]:
    """
    Runs every frame: each bone's matrix to its constraint set, a warm-started solve. on_frame(record, lattice (n, 3), surface (k, 3) or None) returning False stops. Returns FrameRecords.
    """
def run_scene(file: SceneFile, options: SolveOptions | None = None, max_frames: int = 0, reactions: bool = True, progress: typing.Any = None, vtu_dir: str | None = None) -> SceneRun:
    """
    Runs the scene's load steps, time steps or rig frames (options: the file's unless given); progress(SceneProgress) after each step or frame; vtu_dir: write a .vtu series and .pvd there. Runs without the GIL. Returns a SceneRun.
    """
def scene_defaults(name: str) -> SceneParameters:
    """
    A built-in scene's default parameters.
    """
def scene_file_keys() -> list[str]:
    """
    Every key a scene file may hold.
    """
def scene_names() -> list[str]:
    """
    The built-in scenes' names.
    """
def shape_deviation(mesh: Mesh, positions: typing.Any) -> ShapeDeviation:
    """
    How far positions (n, 3) are from the rest shape up to a rigid motion.
    """
def split_hexes_into_tets(mesh: Mesh) -> Mesh:
    """
    Each hex of a lattice-like hex8 mesh split into six tets (hex e becomes tets 6e .. 6e+5).
    """
def surface_area(surface: TriangleSurface) -> float:
    """
    Sum of the triangles' areas.
    """
def to_rigid_transform(matrix: typing.Any, center: list[float[3]] = [0.0, 0.0, 0.0]) -> RigidTransform:
    """
    A 4x4 affine bone matrix (last row 0 0 0 1) as a RigidTransform about center.
    """
def uniform_material(mesh: Mesh, material: Material) -> MaterialMap:
    """
    One material for the whole mesh.
    """
def validate_closed_surface(surface: TriangleSurface, name: str = 'surface') -> None:
    """
    snh.Error (starting with name) unless closed and consistently oriented.
    """
def vertex_spacing(mesh: Mesh) -> float:
    """
    (rest volume / vertices in elements)^(1/3).
    """
def vertices_in_box(mesh: Mesh, lo: list[float[3]], hi: list[float[3]]) -> numpy.ndarray[numpy.int32]:
    """
    Vertices with lo <= x <= hi in every coordinate, int32 (k,).
    """
def vertices_in_group(mesh: Mesh, group: typing.Any, dimension: int = -1) -> numpy.ndarray[numpy.int32]:
    """
    The vertices of the group with this name (str) or tag (int).
    """
def vertices_in_sphere(mesh: Mesh, center: list[float[3]], radius: float) -> numpy.ndarray[numpy.int32]:
    """
    Vertices with |x - center| <= radius.
    """
def vertices_on_plane(mesh: Mesh, point: list[float[3]], normal: list[float[3]], tolerance: float = 1e-09) -> numpy.ndarray[numpy.int32]:
    """
    Vertices within tolerance of the plane through point with normal.
    """
def vertices_with_value(mesh: Mesh, array: str, value: float) -> numpy.ndarray[numpy.int32]:
    """
    Vertices whose point-array value equals value.
    """
def vertices_with_value_in(mesh: Mesh, array: str, lo: float, hi: float) -> numpy.ndarray[numpy.int32]:
    """
    Vertices whose value lies in [lo, hi].
    """
def voxelize(surface: TriangleSurface, cell: float, options: VoxelizeOptions | None = None) -> Voxelization:
    """
    Voxelizes a closed surface into a hex8 lattice of cubes of side cell.
    """
def write_checkpoint(path: str, state: SimulationState) -> None:
    """
    Writes a SimulationState to a versioned binary file (doubles bit for bit).
    """
def write_mdd(path: str, cache: PointCache) -> None:
    """
    Writes an MDD point cache (big-endian; one time per sample).
    """
def write_mesh(path: str, mesh: Mesh) -> None:
    """
    Writes the mesh at rest in the format its extension names (.msh, .vtk, .vtu, .mesh, .node/.ele).
    """
def write_obj(path: str, surface: TriangleSurface, positions: typing.Any = None) -> None:
    """
    Writes the surface as OBJ.
    """
def write_obj_surface(path: str, mesh: Mesh, positions: typing.Any = None) -> None:
    """
    The boundary surface as OBJ.
    """
def write_pc2(path: str, cache: PointCache) -> None:
    """
    Writes a PC2 point cache (little-endian).
    """
def write_ply_surface(path: str, mesh: Mesh, positions: typing.Any = None) -> None:
    """
    The boundary surface as PLY.
    """
def write_point_cache(path: str, cache: PointCache) -> None:
    """
    Writes .pc2 or .mdd by the extension.
    """
def write_pvd(path: str, steps: list[tuple[float, str]]) -> None:
    """
    A ParaView collection of (time, relative .vtu path) entries.
    """
def write_scene_json(path: str, file: SceneFile, run: SceneRun) -> None:
    """
    The run's JSON summary (docs/cli.md).
    """
def write_surface_ply(path: str, surface: TriangleSurface, positions: typing.Any = None) -> None:
    """
    Writes the surface as binary PLY at positions (n, 3) (None: its own), vertices in its order.
    """
def write_surface_vtu(path: str, surface: TriangleSurface, positions: typing.Any = None) -> None:
    """
    Writes the surface as .vtu.
    """
def write_vtu(path: str, mesh: Mesh, positions: typing.Any = None, point_fields: typing.Any = None, cell_fields: typing.Any = None) -> None:
    """
    Writes an ASCII .vtu at positions (n, 3) (default: rest). point_fields: {name: (n,) or (n, 3)}; cell_fields: {name: (m,), (m, 3) or (m, 3, 3)}.
    """
