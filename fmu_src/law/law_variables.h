/*
 * What the variable tables of the models built on the law (contact_law.h)
 * share: the enumeration of its sliding rules, the type SlidingRule of both
 * the point's (models/OrthotropicContact/table.h) and the patch's (models/ContactPatch/table.h)
 * slidingRule, in the tables' E(name, value, description) form.  Its values
 * are oc_rule's.
 */
#ifndef OC_LAW_VARIABLES_H
#define OC_LAW_VARIABLES_H

#define OC_SLIDING_RULE_ITEMS(E)                                                               \
    E(associated, 1, "G = F: classical orthotropic Coulomb friction (paper Case 1)")           \
    E(coupled, 2, "G = (B F B)^-1: the coupled law of Konyukhov and Schweizerhof")             \
    E(eq20, 3, "the paper's explicit eq. (20), step-size dependent: for reproduction only")

#endif
