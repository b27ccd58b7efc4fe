"""Literal one-run transcriptions of the authors' C++ codes, plain Python loops, 0-based.

``lshade_cc``: Tanabe's ``lshade.cc`` (L-SHADE 1.1, CEC 2014) and, with ``jso=True``, Brest's
edit of it (jSO, CEC 2017; its lines are marked "jSO" as in the source). ``nl_shade_rsp_cpp``:
Stanovov's ``nl_shade_rsp.cpp`` (CEC 2021), ``Optimizer::MainCycle`` and the functions it calls.

Both follow the sources statement by statement, individual by individual, except where they
call a random number generator: there they take the next number of the draws the batched
code made (one generation's arrays for this run, ``g["u_mem"][i]`` etc.) and turn it into the
value with the law of the source's call, written out here on its own:

* ``rand() % n`` redrawn ``while`` it hits excluded values: the ``floor(u m)``-th of the ``m``
  allowed values, in increasing order (:func:`pick`);
* the CEC 2021 code's retries capped at 25: :func:`capped` (the exact law of "draw, redraw up
  to 25 times while excluded, keep the last");
* ``do F = cauchy(mu, 0.1) while (F <= 0)``: :func:`positive_cauchy`;
* ``gauss(mu, 0.1)`` / ``NormRand``: ``mu + 0.1 z`` with the drawn normal ``z``.

The codes sort with a quicksort; these use Python's sort, the same order when no values tie.
"""

from __future__ import annotations

import math


def c_round(x):
    t = math.trunc(x)
    return int(t + math.copysign(1, x)) if abs(x - t) >= 0.5 else int(t)


def pick(u, allowed):
    """``do r = rand() % n while (r excluded)``: the ``floor(u m)``-th allowed value."""
    return allowed[min(int(u * len(allowed)), len(allowed) - 1)]


def capped(u, weights, excluded, draws):
    """Index drawn with ``weights``, redrawn while in ``excluded``, ``draws`` draws at most."""
    tot = 0.0
    for w in weights:
        tot += w
    q = sum(weights[k] for k in sorted(set(excluded))) / tot
    c = q**draws
    if u < c:
        pool, v = sorted(set(excluded)), u / c
    else:
        pool, v = [k for k in range(len(weights)) if k not in excluded], (u - c) / (1 - c)
    total = 0.0
    for k in pool:
        total += weights[k]
    acc = 0.0
    for k in pool:
        acc += weights[k]
        if acc > v * total:
            return k
    return pool[-1]


def positive_cauchy(mu, u):
    """Cauchy(mu, 0.1) conditioned on > 0, at the uniform ``u`` (upper tail first)."""
    # the C library's atan and tan, as the optimizers take them (mawdo.util.libm): NumPy's
    # differ in the last bits on CPUs with AVX-512
    p0 = 0.5 + math.atan(-mu / 0.1) / math.pi  # P(F <= 0)
    w = p0 + (1.0 - p0) * (1.0 - u)
    return mu + 0.1 * math.tan(math.pi * (w - 0.5))


def modify_solution_with_parent_medium(child, parent, lo, hi):
    for j in range(len(child)):
        if child[j] < lo[j]:
            child[j] = (lo[j] + parent[j]) / 2.0
        elif child[j] > hi[j]:
            child[j] = (hi[j] + parent[j]) / 2.0


def lshade_cc(pop, f, lo, hi, max_num_evaluations, draws, *, p_best_rate, arc_rate, memory_size,
              memory_init, jso=False):  # fmt: skip
    """``LSHADE::run()`` for one run from the initial population ``pop``; ``draws`` holds one
    dict per generation. Returns the population and values after each generation."""
    pop = [list(x) for x in pop]
    pop_size = len(pop)
    fitness = [f(x) for x in pop]
    nfes = pop_size
    arc_size = c_round(pop_size * arc_rate)
    archive = []  # archive[:arc_ind_count]
    memory_sf = [memory_init[0]] * memory_size
    memory_cr = [memory_init[1]] * memory_size
    memory_pos = 0
    p_num = c_round(pop_size * p_best_rate)
    max_pop_size, min_pop_size = pop_size, 4
    out = []
    for g in draws:  # while (nfes < max_num_evaluations)
        sorted_array = sorted(range(pop_size), key=lambda i: fitness[i])
        children, pop_sf, pop_cr = [], [], []
        for target in range(pop_size):
            random_selected_period = int(g["u_mem"][target] * memory_size)
            mu_sf, mu_cr = memory_sf[random_selected_period], memory_cr[random_selected_period]
            if jso and random_selected_period == memory_size - 1:
                mu_sf, mu_cr = 0.9, 0.9
            if (mu_cr < 0) if jso else (mu_cr == -1):
                cr = 0.0
            else:
                cr = mu_cr + 0.1 * g["z"][target]  # gauss(mu_cr, 0.1)
                if cr > 1:
                    cr = 1.0
                elif cr < 0:
                    cr = 0.0
            if jso and nfes < 0.25 * max_num_evaluations and cr < 0.7:
                cr = 0.7
            if jso and nfes < 0.50 * max_num_evaluations and cr < 0.6:
                cr = 0.6
            sf = positive_cauchy(mu_sf, g["u_f"][target])  # do ... while (pop_sf <= 0)
            if sf > 1:
                sf = 1.0
            if jso and nfes < 0.6 * max_num_evaluations and sf > 0.7:
                sf = 0.7
            top = [sorted_array[k] for k in range(p_num)]
            if jso and nfes < 0.50 * max_num_evaluations and len(top) > 1:
                top = [k for k in top if k != target]  # do ... while (p_best_ind == target)
            p_best_ind = pick(g["u_pb"][target], top)
            pop_sf.append(sf)
            pop_cr.append(cr)
            children.append(
                current_to_pbest(
                    pop,
                    archive,
                    target,
                    p_best_ind,
                    sf,
                    cr,
                    g,
                    nfes,
                    max_num_evaluations,
                    jso,
                    lo,
                    hi,
                )  # fmt: skip
            )
        children_fitness = [f(x) for x in children]
        nfes += pop_size
        success_sf, success_cr, dif_fitness = [], [], []
        for i in range(pop_size):  # generation alternation
            if children_fitness[i] == fitness[i]:
                pop[i] = list(children[i])
            elif children_fitness[i] < fitness[i]:
                dif_fitness.append(abs(fitness[i] - children_fitness[i]))
                fitness[i] = children_fitness[i]
                success_sf.append(pop_sf[i])
                success_cr.append(pop_cr[i])
                if arc_size > 1:
                    if len(archive) < arc_size:
                        archive.append(list(pop[i]))
                    else:
                        archive[int(g["u_slot"][i] * arc_size)] = list(pop[i])
                pop[i] = list(children[i])
        if success_sf:
            memory_pos = update_memory(memory_sf, memory_cr, memory_pos, success_sf, success_cr,
                                       dif_fitness, jso)  # fmt: skip
        plan_pop_size = c_round(
            (((min_pop_size - max_pop_size) / float(max_num_evaluations)) * nfes) + max_pop_size
        )
        if pop_size > plan_pop_size:
            reduction_ind_num = pop_size - plan_pop_size
            if pop_size - reduction_ind_num < min_pop_size:
                reduction_ind_num = pop_size - min_pop_size
            for _ in range(reduction_ind_num):  # reducePopulationWithSort
                worst_ind = 0
                for j in range(1, pop_size):
                    if fitness[j] > fitness[worst_ind]:
                        worst_ind = j
                del pop[worst_ind], fitness[worst_ind]
                pop_size -= 1
            arc_size = int(pop_size * arc_rate)
            del archive[arc_size:]  # if (arc_ind_count > arc_size) arc_ind_count = arc_size
            if jso:
                p_best_rate_now = p_best_rate * (1.0 - 0.5 * nfes / float(max_num_evaluations))
            else:
                p_best_rate_now = p_best_rate
            p_num = c_round(pop_size * p_best_rate_now)
            if p_num <= 1:
                p_num = 2
        out.append(([list(x) for x in pop], list(fitness), list(memory_sf), list(memory_cr)))
    return out


def current_to_pbest(pop, archive, target, p_best, sf, cr, g, nfes, max_nfes, jso, lo, hi):
    """``operateCurrentToPBest1BinWithArchive``."""
    pop_size, problem_size = len(pop), len(pop[0])
    jF = sf
    if jso:
        if nfes < 0.2 * max_nfes:
            jF = jF * 0.7
        elif nfes < 0.4 * max_nfes:
            jF = jF * 0.8
        else:
            jF = jF * 1.2
    r1 = pick(g["u_r1"][target], [k for k in range(pop_size) if k != target])
    allowed = [k for k in range(pop_size + len(archive)) if k not in (target, r1)]
    r2 = pick(g["u_r2"][target], allowed)
    random_variable = int(g["u_j"][target] * problem_size)
    x2 = archive[r2 - pop_size] if r2 >= pop_size else pop[r2]
    child = []
    for i in range(problem_size):
        if g["u_cr"][target][i] < cr or i == random_variable:
            x = pop[target][i]
            child.append(x + jF * (pop[p_best][i] - x) + sf * (pop[r1][i] - x2[i]))
        else:
            child.append(pop[target][i])
    modify_solution_with_parent_medium(child, pop[target], lo, hi)
    return child


def update_memory(memory_sf, memory_cr, memory_pos, success_sf, success_cr, dif_fitness, jso):
    """The weighted Lehmer mean update; returns the new ``memory_pos``."""
    old_sf, old_cr = memory_sf[memory_pos], memory_cr[memory_pos]
    memory_sf[memory_pos] = 0.0
    memory_cr[memory_pos] = 0.0
    temp_sum_sf = temp_sum_cr = total = 0.0
    for d in dif_fitness:
        total += d
    for i in range(len(success_sf)):
        weight = dif_fitness[i] / total
        memory_sf[memory_pos] += weight * success_sf[i] * success_sf[i]
        temp_sum_sf += weight * success_sf[i]
        memory_cr[memory_pos] += weight * success_cr[i] * success_cr[i]
        temp_sum_cr += weight * success_cr[i]
    memory_sf[memory_pos] /= temp_sum_sf
    if temp_sum_cr == 0 or memory_cr[memory_pos] == -1:
        memory_cr[memory_pos] = -1
    else:
        memory_cr[memory_pos] /= temp_sum_cr
    if jso:
        memory_sf[memory_pos] = (memory_sf[memory_pos] + old_sf) / 2.0
        memory_cr[memory_pos] = (memory_cr[memory_pos] + old_cr) / 2.0
    return (memory_pos + 1) % len(memory_sf)


def nl_shade_rsp_cpp(popul, f, left, right, max_fe_val, draws, *, memory_size, arch_param=2.1,
                     memory_init=0.2):  # fmt: skip
    """``Optimizer::MainCycle()`` for one run from the initial population ``popul``; returns
    the population, values and memories after each generation."""
    popul = [list(x) for x in popul]
    n_inds = n_inds_max = len(popul)
    n_inds_min, n_vars = 4, len(popul[0])
    archive_size = int(n_inds_max * arch_param)
    archive = []  # Archive[:CurrentArchiveSize]
    memory_f = [memory_init] * memory_size
    memory_cr = [memory_init] * memory_size
    memory_iter = 0
    fit_mass = [f(x) for x in popul]
    nfe = n_inds
    arch_probs = 0.5
    out = []
    for g in draws:  # do { ... } while (NFEval < MaxFEval)
        indexes = sorted(range(n_inds), key=lambda i: fit_mass[i])
        back_indexes = [indexes.index(i) for i in range(n_inds)]
        fit_temp3 = [math.exp(-float(i) / float(n_inds)) for i in range(n_inds)]
        psizeval = int(max(2.0, n_inds * (0.2 / float(max_fe_val) * float(nfe) + 0.2)))
        cross_exponential = 1 if g["u_exp"][0] < 0.5 else 0
        f_generated, cr_generated = [], []
        for i in range(n_inds):
            m = int(g["u_mem"][i] * memory_size)
            cr = min(1.0, max(0.0, memory_cr[m] + 0.1 * g["z"][i]))
            F = positive_cauchy(memory_f[m], g["u_f"][i])  # do ... while (F <= 0)
            f_generated.append(min(F, 1.0))
            cr_generated.append(cr)
        cr_generated.sort()  # qSort1
        success, popul_temp, fit_mass_temp, arch_usages = [], [], [], []
        for i in range(n_inds):
            excl = [back_indexes[i]] if back_indexes[i] < psizeval else []
            r0 = indexes[capped(g["u_pb"][i], [1.0] * psizeval, excl, 26)]
            r1 = capped(g["u_r1"][i], [1.0] * n_inds, [r0], 25)  # GenerateNextRandUnif
            if g["u_arc"][i] > arch_probs or len(archive) == 0:
                ranks = [back_indexes[i], back_indexes[r0], back_indexes[r1]]
                x2 = popul[indexes[capped(g["u_r2"][i], fit_temp3, ranks, 26)]]
                arch_usages.append(0)
            else:
                x2 = archive[int(g["u_r2"][i] * len(archive))]  # GenerateNextRandUnifOnlyArch
                arch_usages.append(1)
            x, fi = popul[i], f_generated[i]
            donor = [x[j] + fi * (popul[r0][j] - x[j]) + fi * (popul[r1][j] - x2[j])
                     for j in range(n_vars)]  # fmt: skip
            will_crossover = int(g["u_j"][i] * n_vars)
            cr = cr_generated[back_indexes[i]]
            cr_to_use = 0.0
            if nfe > 0.5 * max_fe_val:
                cr_to_use = (float(nfe) / float(max_fe_val) - 0.5) * 2
            if cross_exponential == 0:
                trial = [donor[j] if (g["u_cr"][i][j] < cr_to_use or will_crossover == j) else x[j]
                         for j in range(n_vars)]  # fmt: skip
            else:
                start_loc = int(g["u_start"][i] * n_vars)
                L, t = start_loc + 1, 0
                while g["u_cr"][i][t] < cr and L < n_vars:
                    L, t = L + 1, t + 1
                trial = list(x)
                for j in range(start_loc, L):
                    trial[j] = donor[j]
            for j in range(n_vars):  # FindLimits
                if trial[j] < left[j] or trial[j] > right[j]:
                    trial[j] = g["u_box"][i][j] * (right[j] - left[j]) + left[j]
            popul_temp.append(trial)
            fit_mass_temp.append(f(trial))
            nfe += 1
            if fit_mass_temp[i] < fit_mass[i]:  # SaveSuccessCrF(Cr, F, ...): the member F
                success.append((cr, F, abs(fit_mass[i] - fit_mass_temp[i])))
        arch_success = no_arch_success = n_arch_usages = 0.0
        for i in range(n_inds):
            if fit_mass_temp[i] <= fit_mass[i]:
                gain = cdiv(fit_mass[i] - fit_mass_temp[i], fit_mass[i])
                if arch_usages[i] == 1:
                    arch_success += gain
                    n_arch_usages += 1
                else:
                    no_arch_success += gain
                if len(archive) < archive_size:  # CopyToArchive
                    archive.append(list(popul[i]))
                elif archive_size > 0:
                    archive[int(g["u_slot"][i] * archive_size)] = list(popul[i])
                popul[i] = popul_temp[i]
                fit_mass[i] = fit_mass_temp[i]
        if n_arch_usages != 0:
            arch_success = cdiv(arch_success, n_arch_usages)
            no_arch_success = cdiv(no_arch_success, n_inds - n_arch_usages)
            arch_probs = cdiv(arch_success, arch_success + no_arch_success)
            arch_probs = max(0.1, min(0.9, arch_probs))
            if arch_success == 0:
                arch_probs = 0.5
        else:
            arch_probs = 0.5
        x_fe = float(nfe) / float(max_fe_val)
        raw = c_round((n_inds_min - n_inds_max) * math.pow(x_fe, 1.0 - x_fe) + n_inds_max)
        new_n_inds = min(max(raw, n_inds_min), n_inds_max)
        new_arch_size = int(raw * arch_param)
        if new_arch_size < n_inds_min:
            new_arch_size = n_inds_min
        archive_size = new_arch_size
        del archive[archive_size:]
        popul, fit_mass = remove_worst(popul, fit_mass, n_inds, new_n_inds)
        n_inds = new_n_inds
        if success:  # UpdateMemoryCrF
            memory_cr[memory_iter] = mean_wl([s[0] for s in success], [s[2] for s in success])
            memory_f[memory_iter] = mean_wl([s[1] for s in success], [s[2] for s in success])
            memory_iter = (memory_iter + 1) % memory_size
        else:
            memory_f[memory_iter] = 0.5
            memory_cr[memory_iter] = 0.5
        out.append(([list(x) for x in popul], list(fit_mass), list(memory_f), list(memory_cr)))
    return out


def remove_worst(popul, fit_mass, n_inds, new_n_inds):
    """``RemoveWorst(NInds, NewNInds)`` as written (``NInds`` is not decremented), then the
    first ``NewNInds`` kept (``NInds = newNInds``)."""
    popul, fit_mass = list(popul), list(fit_mass)
    for _ in range(n_inds - new_n_inds):
        worst_num = 0
        for i in range(1, n_inds):
            if fit_mass[i] > fit_mass[worst_num]:
                worst_num = i
        for i in range(worst_num, n_inds - 1):
            popul[i] = popul[i + 1]
            fit_mass[i] = fit_mass[i + 1]
    return popul[:new_n_inds], fit_mass[:new_n_inds]


def cdiv(a, b):
    """C's double division: IEEE results (inf, NaN) where Python raises."""
    a, b = float(a), float(b)
    if b != 0 or math.isnan(b):
        return a / b
    if a == 0 or math.isnan(a):
        return math.nan
    return math.copysign(math.inf, a) * math.copysign(1.0, b)


def mean_wl(vector, temp_weights):
    """``MeanWL_general(Vector, TempWeights, Size, 2, 1)``."""
    sum_weight = sum_square = total = 0.0
    for w in temp_weights:
        sum_weight += w
    weights = [w / sum_weight for w in temp_weights]
    for i in range(len(vector)):
        sum_square += weights[i] * math.pow(vector[i], 2)
    for i in range(len(vector)):
        total += weights[i] * math.pow(vector[i], 1)
    return sum_square / total if abs(total) > 0.000001 else 0.5
