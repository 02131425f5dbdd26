/* The per-vertex terms a scene compiles into the kernels (kernels/fem.cl,
 * kernels/multigrid.cl; set by the host's ElasticModel, solver/model/elastic_model.h),
 * 0 where the build leaves them out. */
#ifndef SNH_FEM_VERTEX_TERMS_H
#define SNH_FEM_VERTEX_TERMS_H

#ifndef SNH_INERTIA
#define SNH_INERTIA 0
#endif
#ifndef SNH_OBSTACLES
#define SNH_OBSTACLES 0
#endif
#ifndef SNH_SELF_CONTACT
#define SNH_SELF_CONTACT 0
#endif
#ifndef SNH_FRICTION
#define SNH_FRICTION 0
#endif
/* Barrier self-contact (solver/contact/barrier_terms.h): its products run in
 * contact/barrier_pairs.cl; block-Jacobi's setup adds its diagonal blocks. */
#ifndef SNH_SELF_BARRIER
#define SNH_SELF_BARRIER 0
#endif
/* An embedded surface in contact with the obstacles (with SNH_OBSTACLES only;
 * solver/model/vertex_terms.h): snh_contact_vertices adds its points' shares. */
#ifndef SNH_SURFACE_CONTACT
#define SNH_SURFACE_CONTACT 0
#endif
#define SNH_VERTEX_TERMS (SNH_INERTIA || SNH_OBSTACLES || SNH_SELF_CONTACT)

#endif
