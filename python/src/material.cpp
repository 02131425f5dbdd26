// Materials and per-region material maps (snh/material.h, regions.h).
#include "snh/material.h"

#include "common.h"
#include "snh/regions.h"
#include "snh/simulation.h"

namespace snh_python {

namespace {

snh::MaterialModel model_of(py::handle model) {
  if (py::isinstance<py::str>(model)) return snh::parse_material_model(model.cast<std::string>());
  return model.cast<snh::MaterialModel>();
}

}  // namespace

void bind_material(py::module_& m) {
  py::enum_<snh::Barrier>(m, "Barrier", "Whether Stable Neo-Hookean carries the origin barrier term.")
      .value("on", snh::Barrier::on)
      .value("off", snh::Barrier::off);

  py::enum_<snh::MaterialModel>(m, "MaterialModel", "The material family (one kernel file each).")
      .value("stable_neo_hookean", snh::MaterialModel::stable_neo_hookean)
      .value("fung", snh::MaterialModel::fung)
      .value("arruda_boyce", snh::MaterialModel::arruda_boyce)
      .value("corotational", snh::MaterialModel::corotational)
      .value("fixed_corotational", snh::MaterialModel::fixed_corotational)
      .value("stvk_kikuuwe", snh::MaterialModel::stvk_kikuuwe)
      .value("neohookean", snh::MaterialModel::neohookean);

  py::class_<snh::LameParameters>(m, "LameParameters", "Small-strain Lame moduli.")
      .def(py::init([](double mu, double lambda_) {
             return snh::LameParameters{mu, lambda_};
           }),
           py::arg("mu"), py::arg("lambda_"), "Shear modulus mu and first Lame parameter lambda.")
      .def_readwrite("mu", &snh::LameParameters::mu, "Shear modulus.")
      .def_readwrite("lambda_", &snh::LameParameters::lambda, "First Lame parameter.")
      .def("__repr__", [](const snh::LameParameters& l) {
        return "LameParameters(mu=" + std::to_string(l.mu) + ", lambda_=" + std::to_string(l.lambda) + ")";
      });

  py::class_<snh::MaterialOptions>(m, "MaterialOptions",
                                   "Model-specific settings for building a material from (E, nu).")
      .def(py::init([](const py::kwargs& kw) { return from_kwargs<snh::MaterialOptions>(kw); }),
           "Keyword arguments set the fields of the same names.")
      .def_readwrite("barrier", &snh::MaterialOptions::barrier, "Barrier (snh only), or None: on below nu 0.4.")
      .def_readwrite("fung_gamma", &snh::MaterialOptions::fung_gamma, "gamma / mu_Lame.")
      .def_readwrite("fung_mu1", &snh::MaterialOptions::fung_mu1, "Fung exponent rate.")
      .def_readwrite("arruda_boyce_beta1", &snh::MaterialOptions::arruda_boyce_beta1, "Arruda-Boyce beta1.")
      .def_readwrite("arruda_boyce_beta2", &snh::MaterialOptions::arruda_boyce_beta2, "Arruda-Boyce beta2.")
      .def_readwrite("kikuuwe_kappa", &snh::MaterialOptions::kikuuwe_kappa, "kappa / mu_Lame.")
      .def_readwrite("neohookean_j0", &snh::MaterialOptions::neohookean_j0, "Inversion handling below J0.")
      .def_readwrite("alpha", &snh::MaterialOptions::alpha, "Chen and Barbic 2024 nonlinearity alpha.")
      .def_readwrite("lambda_model", &snh::MaterialOptions::lambda_model, "Model of the lambda part, or None.")
      .def_readwrite("alpha_lambda", &snh::MaterialOptions::alpha_lambda, "Alpha of the lambda part, or None.");

  py::class_<snh::StableNeoHookean>(m, "StableNeoHookean", "The Stable Neo-Hookean energy's own parameters.")
      .def_static("from_youngs_modulus", &snh::StableNeoHookean::from_youngs_modulus, py::arg("youngs_modulus"),
                  py::arg("poisson_ratio"), py::arg("barrier") = py::none(),
                  "From E and nu with the paper's reparameterization (snh.Error for out-of-range values).")
      .def_static("from_lame", &snh::StableNeoHookean::from_lame, py::arg("lame"), py::arg("barrier") = py::none(),
                  "From the Lame moduli.")
      .def_readonly("mu", &snh::StableNeoHookean::mu, "The energy's mu.")
      .def_readonly("lambda_", &snh::StableNeoHookean::lambda, "The energy's lambda.")
      .def_readonly("barrier", &snh::StableNeoHookean::barrier, "Whether the barrier term is present.")
      .def("lame", &snh::StableNeoHookean::lame, "The small-strain moduli this energy reproduces.")
      .def("youngs_modulus", &snh::StableNeoHookean::youngs_modulus, "Small-strain Young's modulus.")
      .def("poisson_ratio", &snh::StableNeoHookean::poisson_ratio, "Small-strain Poisson's ratio.");

  py::class_<snh::Material>(m, "Material", "Any material model with its parameters.")
      .def(py::init<>(), "A zero material; build one with from_youngs_modulus or from_lame.")
      .def(py::init<const snh::StableNeoHookean&>(), py::arg("snh"), "The Stable Neo-Hookean material.")
      .def_static(
          "from_youngs_modulus",
          [](double e, double nu, py::handle model, std::optional<snh::MaterialOptions> options) {
            return snh::Material::from_youngs_modulus(model_of(model), e, nu, options.value_or(snh::MaterialOptions{}));
          },
          py::arg("youngs_modulus"), py::arg("poisson_ratio"),
          py::arg("model") = snh::MaterialModel::stable_neo_hookean, py::arg("options") = py::none(),
          "A material of `model` (MaterialModel or its name, e.g. 'snh') with small-strain moduli (E, nu); "
          "snh.Error for out-of-range values.")
      .def_static(
          "from_lame",
          [](const snh::LameParameters& lame, py::handle model, std::optional<snh::MaterialOptions> options) {
            return snh::Material::from_lame(model_of(model), lame, options.value_or(snh::MaterialOptions{}));
          },
          py::arg("lame"), py::arg("model") = snh::MaterialModel::stable_neo_hookean, py::arg("options") = py::none(),
          "A material of `model` with the given small-strain Lame moduli.")
      .def_readwrite("model", &snh::Material::model, "MaterialModel.")
      .def_readwrite("mu", &snh::Material::mu, "The energy's mu.")
      .def_readwrite("lambda_", &snh::Material::lambda, "The energy's lambda.")
      .def_readwrite("c0", &snh::Material::c0, "First model-specific parameter.")
      .def_readwrite("c1", &snh::Material::c1, "Second model-specific parameter.")
      .def_readwrite("barrier", &snh::Material::barrier, "Whether the snh barrier term is present.")
      .def("lame", &snh::Material::lame, "The small-strain Lame moduli.")
      .def("defined_for_inversion", &snh::Material::defined_for_inversion, "Whether psi is defined for every F.")
      .def_property_readonly("description", &snh::Material::description, "E.g. 'snh' or 'snh alpha=1.5'.")
      .def("__repr__", [](const snh::Material& mat) {
        return "Material(" + mat.description() + ", mu=" + std::to_string(mat.mu) +
               ", lambda_=" + std::to_string(mat.lambda) + ")";
      });
  py::implicitly_convertible<snh::StableNeoHookean, snh::Material>();

  py::class_<snh::MaterialRegion>(m, "MaterialRegion", "A named set of elements with its own material.")
      .def(py::init([](std::string name, py::handle elements, snh::Material material) {
             return snh::MaterialRegion{std::move(name), to_indices(elements, "elements", 0, -1), material};
           }),
           py::arg("name"), py::arg("elements"), py::arg("material"), "Region `name` of `elements` with `material`.")
      .def_readwrite("name", &snh::MaterialRegion::name, "Region name.")
      .def_property(
          "elements",
          [](const snh::MaterialRegion& r) { return copy_array(r.elements, {py::ssize_t(r.elements.size())}); },
          [](snh::MaterialRegion& r, py::handle v) { r.elements = to_indices(v, "elements", 0, -1); },
          "Element indices, int32 (k,).")
      .def_readwrite("material", &snh::MaterialRegion::material, "The region's Material.");

  py::class_<snh::MaterialMap>(m, "MaterialMap",
                               "The material of every element: element e uses materials[element_material[e]].")
      .def_readwrite("materials", &snh::MaterialMap::materials, "Materials: 0 the base, k+1 region k (a copy).")
      .def_property(
          "element_material",
          [](const snh::MaterialMap& mm) {
            return copy_array(mm.element_material, {py::ssize_t(mm.element_material.size())});
          },
          [](snh::MaterialMap& mm, py::handle v) {
            mm.element_material = to_indices(v, "element_material", 0, static_cast<int64_t>(mm.materials.size()));
          },
          "Index into materials per element, int32 (m,).")
      .def_readwrite("names", &snh::MaterialMap::names, "'base', then the regions' names.")
      .def_property_readonly("uniform", &snh::MaterialMap::uniform, "True for one material.");

  m.def("uniform_material", &snh::uniform_material, py::arg("mesh"), py::arg("material"),
        "One material for the whole mesh.");
  m.def("make_material_map", &snh::make_material_map, py::arg("mesh"), py::arg("base"), py::arg("regions"),
        "Base material plus regions (snh.Error for an empty region, an index out of range, an element in two).");
  m.def("max_poisson_ratio", &snh::max_poisson_ratio, py::arg("materials"),
        "The largest small-strain Poisson's ratio over the materials some element uses.");
}

}  // namespace snh_python
