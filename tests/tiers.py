"""The test tiers.  `make check` (tools/run_tests.sh --fast) runs every test not
marked `slow`: the law, both FMUs, the rig (harness, compiled master,
CarriageBlock), the contact patch and the CLI's core, with the release C tests.
`make test` runs everything, and is what CI runs.

SLOW lists the slow tests by file (its path under tests/) and function name
(every parametrization of a function; "*" for a whole file), measured with
`pytest --durations=0`:
installs into fresh environments, the FMU rebuilt from its sources, qemu, the
long random and reference comparisons, identification, uncertainty
propagation and sensitivity.  The list is kept in one place, not spread as
decorators, so that moving tests between files means moving names here; an
entry naming a file that does not exist, or a function its file no longer
has, is an error (conftest.py), so the list cannot go stale silently.
"""
from __future__ import annotations

from pathlib import Path

import pytest

from paths import TESTS

SLOW = {
    "identification/test_job.py": "*",         # identification: FMU data, CLI runs
    "identification/test_estimators.py": "*",  # coverage over 100 replicates; 120 sets of raw recordings
    "identification/test_report.py": {   # identifies the bundled recordings
        "test_the_recordings_fit_figure_draws_the_fitted_model_through_the_runs",
        "test_identify_prints_every_estimate_with_its_unit_and_positive_intervals",
    },
    "identification/test_design.py": {   # 200 joint fits; the others: CLI runs and plans, 4-8 s
        "test_the_joint_fits_spread_over_noisy_rig_runs_is_the_predicted_sd",
        "test_the_next_runs_given_those_made_complete_the_best_design",
        "test_a_prior_from_an_identification_brings_its_estimates_rig_and_noise",
        "test_a_criterion_minimises_the_relative_variances",
    },
    "identification/test_strip_model.py": {
        "test_strip_viscosity_estimated_from_two_velocities_through_the_cli",
        "test_known_strip_is_an_input_and_one_velocity_cannot_give_the_viscosity",
    },
    "identification/test_export.py": {   # identifies the bundled recordings twice
        "test_force_logs_changed_after_identify_are_refused_by_export_and_uq_naming_them",
        # an identify and two exports per unit slip: 3-5 s each
        "test_a_unit_slip_identify_warns_about_is_refused_by_export_unless_forced",
    },
    "output/test_folder.py": {"test_identify_twice_into_one_folder_leaves_only_the_second_runs_outputs",
                           "test_reproduce_into_the_same_folder_leaves_no_scenario_of_the_earlier_run",
                           "test_a_killed_runs_staging_folder_goes_with_the_next_run_and_a_live_ones_stays"},
    "test_textfiles.py": {   # every file format and case through identify, run and uq
        "test_reduced_data_every_file_every_case",
        "test_raw_recordings_every_file_altered_read_as_the_original",
        "test_raw_recordings_with_decimal_commas_in_a_comma_file_are_one_line",
        "test_a_scenario_file_every_case",
        "test_identified_json_with_a_bom_or_crlf_is_read",
    },
    "uq/test_propagate.py": "*",               # uncertainty propagation, Dask clusters
    "uq/test_estimates.py": "*",
    "uq/test_source.py": "*",                  # an identify and a uq run
    "runs/test_cluster.py": {"test_a_dask_run_leaves_nothing_in_the_temp_folder",
                             "test_sweeps_on_dask_give_the_local_results",
                             "test_a_local_cluster_listens_on_the_loopback_interface_only",
                             "test_no_dask_process_outlives_the_command"},   # Dask clusters
    "runtime/test_processes.py": {   # 4 workers per core
        "test_no_worker_outlives_the_main_process_at_the_most_workers"},
    "runs/test_progress.py": {   # runs long enough for their progress lines
        "test_the_sweeps_refinement_and_recordings_say_they_are_running",
        "test_a_long_run_says_how_far_it_is_within_2_s_and_stops_on_ctrl_c"},
    "runtime/test_interrupts.py": {"test_a_dask_run_signalled_after_writing_everything_reports_success",
                               "test_ctrl_c_on_uq_is_one_line_and_leaves_nothing"},   # uq runs to interrupt
    "runtime/test_temp.py": {"test_ctrl_c_on_reproduce_leaves_no_unpacked_fmu",
                             "test_a_killed_commands_folder_goes_with_the_next_command"},
    "runs/test_size.py": {"test_uqs_estimate_is_the_runs_it_makes",    # identifies the example first
                          "test_identifys_estimate_is_its_validations_runs",   # the recordings: 19 s
                          "test_identify_refuses_validation_runs_above_the_limits"},   # an identify run
    "reproduction/test_sensitivity.py": "*",   # the rig's assumptions, 168 rig runs
    "contracts/test_install.py": {"test_editable_install_finds_its_fmus_and_runs"},   # a fresh venv
    "contracts/test_doc_blocks.py": {"test_slow_page"},   # the pages' blocks marked slow: identify, run, uq
    "contracts/test_cli_fuzz.py": {"test_hostile_runs_of_every_command_end_without_a_traceback"},   # 40 runs
    "fmus/test_model_structure.py": {   # n1, n2 at five values at each base point: 3-8 s
        "test_the_patchs_declared_dependencies_are_what_the_binary_does",
        "test_the_pads_declared_dependencies_are_what_the_binary_does"},
    "fmus/test_platforms.py": {"test_aarch64_linux_binary_runs_under_qemu_like_the_x86_64_one"},
    "fmus/test_windows.py": "*",   # builds two hosts with zig, starts a wine prefix: 20 s warm
    "fmus/test_fmu.py": {"test_sources_compile_into_a_working_binary"},           # builds from sources/
    "closed_forms/test_rig.py": {
        "test_strip_steady_state_matches_the_independent_reference_simulator",
        "test_no_nan_and_no_exception_in_any_regime",
        "test_array_form_equals_the_scalar_form",
        "test_strip_steady_state_matches_the_rig_on_1000_random_laws",
    },
    "rig/test_checks.py": {
        "test_the_identifications_validation_runs_the_fitted_strip",
        "test_a_dynamic_rig_that_never_settled_is_flagged_everywhere",
        "test_a_new_scenario_gets_a_rig_that_settles",
        "test_a_default_travel_the_law_cannot_settle_in_is_refused",
        "test_identify_no_longer_ends_in_a_traceback_on_case5_material_with_a_viscous_strip",
        "test_eq20_runs_are_marked_but_not_warned_about",
    },
    "reproduction/test_planar_outputs.py": {   # orthocontact run of a twist and of towed blocks
        "test_twist_run_checks_itself_against_both_closed_forms",
        "test_towed_block_run_gives_the_closed_form_yaw_at_every_mat_angle",
        "test_an_unsettled_towed_block_is_said_not_passed",
        # 32 x 32 cells, twice
        "test_a_twist_that_stops_before_its_plateau_says_not_checked_and_the_angle_it_needs",
    },
    "reproduction/test_pushed_outputs.py": {   # the bundled push, 16 runs and 4 again on FMI 3.0
        "test_the_bundled_push_shows_full_contact_lift_off_and_tipping_at_the_thresholds",
    },
    "experiment/test_scenario.py": {   # 48 scenarios drawn from the schema, each through `orthocontact run`
        "test_every_scenario_the_schema_accepts_ends_in_a_result_or_one_line",
    },
    "contracts/test_docs_numbers.py": {   # uq on the example, as the guide has it
        "test_the_uq_guides_example_prints_what_the_guide_says",
    },
    "identification/test_recordings.py": {   # identify and uq on recordings
        "test_bundled_recordings_identify_and_uq_by_the_guides_commands",
        "test_intervals_cover_on_synthetic_recordings",
    },
    "identification/test_identified_file.py": {   # identify on the recordings, validated
        "test_raw_recordings_validated_and_with_the_fmu_hold_to_the_schema_too",
    },
    "identification/test_measurements.py": {   # an identify run
        "test_excel_csv_utf8_with_a_byte_order_mark_is_read",
    },
    "identification/test_reduction.py": {   # 300 ramp runs
        "test_ramp_stiffness_is_unbiased_under_the_force_sensors_noise",
    },
    "cli/test_main.py": {   # an identify and a uq run
        "test_uq_at_a_step_that_never_settles_prints_no_warning_text",
    },
}



def mark_slow(config, items) -> None:
    """Marks the items SLOW names; raises pytest.UsageError for a stale entry."""
    missing = sorted(f for f in SLOW if not (TESTS / f).is_file())
    if missing:
        raise pytest.UsageError(f"tests/tiers.py names files that do not exist: {missing}")
    seen: dict[str, set] = {}
    for item in items:
        path = Path(str(item.fspath))
        if TESTS not in path.parents:
            continue
        rel = path.relative_to(TESTS).as_posix()
        if rel not in SLOW:
            continue
        name = getattr(item, "originalname", item.name)
        seen.setdefault(rel, set()).add(name)
        names = SLOW[rel]
        if names == "*" or name in names:
            item.add_marker(pytest.mark.slow)
    if _collected_in_part(config):
        return
    for f, names in SLOW.items():
        if names != "*" and f in seen:   # the file was collected: all its entries must exist
            stale = sorted(set(names) - seen[f])
            if stale:
                raise pytest.UsageError(f"tests/tiers.py: {f} has no test {stale}")


def _collected_in_part(config) -> bool:
    """Files collected only in part (file.py::name, --lf, --sw), where a name
    not collected says nothing."""
    return (any("::" in str(a) for a in config.args)
            or any(config.getoption(o, False) for o in ("lf", "failedfirst", "stepwise")))
