/* SPDX-License-Identifier: Apache-2.0 */
/**
 * @file precision.h
 * @brief The float build's link names: every public function of the float library carries the
 * suffix `_f32` behind its usual name, so that code compiled for one precision does not link
 * against the library of the other.
 *
 * Licensed under the Apache License 2.0 (LICENSE).
 *
 * ::sms_real is `float` or `double` depending on `SMS_USE_FLOAT` (types.h), and so are the
 * layouts of every instance struct and the meaning of every `sms_real *`. An object compiled
 * with `-DSMS_USE_FLOAT` and linked against the double library (or the other way round) would
 * link cleanly and compute garbage (a unit step through a chain printed 3.3e-15 instead of
 * 0.060473). With this header (included by types.h, so by every public header) a float
 * translation unit that calls `sms_chain_step` references `sms_chain_step_f32`, which only the
 * float library defines, and a double one references `sms_chain_step`, which only the double
 * library defines: a mix fails at link time with an undefined reference that names the
 * precision. Source code is unchanged (the usual names are the API); both libraries can be
 * linked into one program. ctest `precision_mix_fails_to_link` builds both mixes and checks
 * that each fails, and that the matching ones link and run.
 *
 * `SMS_NO_PRECISION_SUFFIX` turns the renaming off; only the Python binding's declaration
 * parser defines it (it declares the usual names; the code it compiles includes the headers
 * without it, so it calls the suffixed functions). A function added to a public header gets
 * its line here: the export test of the shared float library fails until it has one.
 */
#ifndef SMOOTHSHAPER_PRECISION_H
#define SMOOTHSHAPER_PRECISION_H

#if defined(SMS_USE_FLOAT) && !defined(SMS_NO_PRECISION_SUFFIX)
/* chain.h */
#define sms_chain_memory_size sms_chain_memory_size_f32
#define sms_chain_init sms_chain_init_f32
#define sms_chain_reset sms_chain_reset_f32
#define sms_chain_step sms_chain_step_f32
#define sms_chain_process sms_chain_process_f32
#define sms_chain_length sms_chain_length_f32
#define sms_chain_input_max sms_chain_input_max_f32
#define sms_chain_hold sms_chain_hold_f32
#define sms_chain_hold_cost sms_chain_hold_cost_f32
#define sms_chain_settle_bound sms_chain_settle_bound_f32
#define sms_chain_advance sms_chain_advance_f32
#define sms_chain_settle sms_chain_settle_f32
#define sms_chain_state_count sms_chain_state_count_f32
#define sms_chain_get_state sms_chain_get_state_f32
#define sms_chain_set_state sms_chain_set_state_f32
#define sms_chain_check_state_range sms_chain_check_state_range_f32
#define sms_chain_rebind sms_chain_rebind_f32
/* coeffs.h */
#define sms_stage_coeffs_make sms_stage_coeffs_make_f32
#define sms_stage_coeffs_memory_size sms_stage_coeffs_memory_size_f32
#define sms_stage_init_coeffs sms_stage_init_coeffs_f32
#define sms_chain_coeffs_memory_size sms_chain_coeffs_memory_size_f32
#define sms_chain_init_coeffs sms_chain_init_coeffs_f32
#define sms_smoother_init_coeffs sms_smoother_init_coeffs_f32
#define sms_shaper_init_coeffs sms_shaper_init_coeffs_f32
#define sms_notch_init_coeffs sms_notch_init_coeffs_f32
/* config.h */
#define sms_stage_config_default sms_stage_config_default_f32
#define sms_stage_config_validate sms_stage_config_validate_f32
/* design.h */
#define sms_design_for_mode sms_design_for_mode_f32
#define sms_identify_from_peaks sms_identify_from_peaks_f32
#define sms_identify_from_record sms_identify_from_record_f32
/* multi_generator.h */
#define sms_multi_generator_reach sms_multi_generator_reach_f32
#define sms_multi_generator_memory sms_multi_generator_memory_f32
#define sms_multi_generator_init sms_multi_generator_init_f32
#define sms_multi_generator_reset sms_multi_generator_reset_f32
#define sms_multi_generator_step sms_multi_generator_step_f32
#define sms_multi_generator_process sms_multi_generator_process_f32
#define sms_multi_generator_busy sms_multi_generator_busy_f32
#define sms_multi_generator_check_target sms_multi_generator_check_target_f32
#define sms_multi_generator_step_target sms_multi_generator_step_target_f32
#define sms_multi_generator_process_targets sms_multi_generator_process_targets_f32
#define sms_multi_generator_start sms_multi_generator_start_f32
#define sms_multi_generator_arrival sms_multi_generator_arrival_f32
#define sms_multi_generator_hold sms_multi_generator_hold_f32
#define sms_multi_phase_duration sms_multi_phase_duration_f32
#define sms_multi_generator_state_count sms_multi_generator_state_count_f32
#define sms_multi_generator_get_state sms_multi_generator_get_state_f32
#define sms_multi_generator_set_state sms_multi_generator_set_state_f32
#define sms_multi_generator_check_state sms_multi_generator_check_state_f32
#define sms_multi_generator_rebind sms_multi_generator_rebind_f32
/* notch.h */
#define sms_notch_init sms_notch_init_f32
#define sms_notch_reset sms_notch_reset_f32
#define sms_notch_step sms_notch_step_f32
#define sms_notch_process sms_notch_process_f32
#define sms_notch_settle_bound sms_notch_settle_bound_f32
#define sms_notch_is_settled sms_notch_is_settled_f32
#define sms_notch_state_count sms_notch_state_count_f32
#define sms_notch_get_state sms_notch_get_state_f32
#define sms_notch_set_state sms_notch_set_state_f32
#define sms_notch_check_state sms_notch_check_state_f32
#define sms_notch_check_state_range sms_notch_check_state_range_f32
#define sms_notch_pole_zeta_from_bandwidth sms_notch_pole_zeta_from_bandwidth_f32
/* shaper.h */
#define sms_shaper_buffer_size sms_shaper_buffer_size_f32
#define sms_shaper_tap_count sms_shaper_tap_count_f32
#define sms_shaper_init sms_shaper_init_f32
#define sms_shaper_reset sms_shaper_reset_f32
#define sms_shaper_step sms_shaper_step_f32
#define sms_shaper_process sms_shaper_process_f32
#define sms_shaper_state_count sms_shaper_state_count_f32
#define sms_shaper_get_state sms_shaper_get_state_f32
#define sms_shaper_set_state sms_shaper_set_state_f32
#define sms_shaper_check_state sms_shaper_check_state_f32
#define sms_shaper_check_state_range sms_shaper_check_state_range_f32
#define sms_shaper_impulses sms_shaper_impulses_f32
#define sms_shaper_taps sms_shaper_taps_f32
#define sms_shaper_transfer sms_shaper_transfer_f32
#define sms_shaper_si_insensitivity sms_shaper_si_insensitivity_f32
#define sms_shaper_si_design sms_shaper_si_design_f32
/* smoother.h */
#define sms_smoother_buffer_size sms_smoother_buffer_size_f32
#define sms_smoother_init sms_smoother_init_f32
#define sms_smoother_reset sms_smoother_reset_f32
#define sms_smoother_input_max sms_smoother_input_max_f32
#define sms_smoother_step sms_smoother_step_f32
#define sms_smoother_process sms_smoother_process_f32
#define sms_smoother_settle_length sms_smoother_settle_length_f32
#define sms_smoother_settle sms_smoother_settle_f32
#define sms_smoother_advance sms_smoother_advance_f32
#define sms_smoother_state_count sms_smoother_state_count_f32
#define sms_smoother_get_state sms_smoother_get_state_f32
#define sms_smoother_set_state sms_smoother_set_state_f32
#define sms_smoother_check_state sms_smoother_check_state_f32
#define sms_smoother_check_state_range sms_smoother_check_state_range_f32
#define sms_smoother_taps sms_smoother_taps_f32
#define sms_smoother_length sms_smoother_length_f32
/* stage.h */
#define sms_stage_memory_size sms_stage_memory_size_f32
#define sms_stage_buffer_size sms_stage_buffer_size_f32
#define sms_stage_init sms_stage_init_f32
#define sms_stage_reset sms_stage_reset_f32
#define sms_stage_step sms_stage_step_f32
#define sms_stage_process sms_stage_process_f32
#define sms_stage_input_max sms_stage_input_max_f32
#define sms_stage_gain_bound sms_stage_gain_bound_f32
#define sms_stage_length sms_stage_length_f32
#define sms_stage_state_count sms_stage_state_count_f32
#define sms_stage_get_state sms_stage_get_state_f32
#define sms_stage_set_state sms_stage_set_state_f32
#define sms_stage_check_state sms_stage_check_state_f32
#define sms_stage_check_state_range sms_stage_check_state_range_f32
#define sms_stage_memory_len sms_stage_memory_len_f32
#define sms_stage_rebind sms_stage_rebind_f32
/* trajectory.h */
#define sms_kinematic_design sms_kinematic_design_f32
#define sms_kinematic_configs sms_kinematic_configs_f32
#define sms_kinematic_design_batch sms_kinematic_design_batch_f32
#define sms_generator_reach sms_generator_reach_f32
#define sms_generator_buffer_size sms_generator_buffer_size_f32
#define sms_generator_init sms_generator_init_f32
#define sms_generator_reset sms_generator_reset_f32
#define sms_generator_step sms_generator_step_f32
#define sms_generator_process sms_generator_process_f32
#define sms_generator_hold sms_generator_hold_f32
#define sms_generator_check_target sms_generator_check_target_f32
#define sms_generator_check_targets sms_generator_check_targets_f32
#define sms_generator_step_target sms_generator_step_target_f32
#define sms_generator_process_targets sms_generator_process_targets_f32
#define sms_generator_hold_target sms_generator_hold_target_f32
#define sms_generator_start sms_generator_start_f32
#define sms_generator_arrival sms_generator_arrival_f32
#define sms_generator_tail_duration sms_generator_tail_duration_f32
#define sms_generator_state_count sms_generator_state_count_f32
#define sms_generator_get_state sms_generator_get_state_f32
#define sms_generator_set_state sms_generator_set_state_f32
#define sms_generator_check_state sms_generator_check_state_f32
#define sms_generator_rebind sms_generator_rebind_f32
#define sms_bspline_buffer_size sms_bspline_buffer_size_f32
#define sms_bspline_init sms_bspline_init_f32
#define sms_bspline_reset sms_bspline_reset_f32
#define sms_bspline_step sms_bspline_step_f32
#define sms_bspline_work_size sms_bspline_work_size_f32
#define sms_bspline_control_points sms_bspline_control_points_f32
#define sms_bspline_pass_sample sms_bspline_pass_sample_f32
#define sms_bspline_period_for_modes sms_bspline_period_for_modes_f32
#define sms_bspline_state_count sms_bspline_state_count_f32
#define sms_bspline_get_state sms_bspline_get_state_f32
#define sms_bspline_set_state sms_bspline_set_state_f32
#define sms_bspline_check_state sms_bspline_check_state_f32
/* types.h */
#define sms_status_string sms_status_string_f32
#define sms_kind_name sms_kind_name_f32
/* align.h */
#define sms_stage_config_lag sms_stage_config_lag_f32
#define sms_chain_config_lag sms_chain_config_lag_f32
#define sms_stage_lag sms_stage_lag_f32
#define sms_chain_lag sms_chain_lag_f32
#define sms_delay_buffer_size sms_delay_buffer_size_f32
#define sms_delay_init sms_delay_init_f32
#define sms_delay_reset sms_delay_reset_f32
#define sms_delay_step sms_delay_step_f32
#define sms_delay_process sms_delay_process_f32
#define sms_delay_settle_length sms_delay_settle_length_f32
#define sms_delay_settle sms_delay_settle_f32
#define sms_delay_advance sms_delay_advance_f32
#define sms_delay_state_count sms_delay_state_count_f32
#define sms_delay_get_state sms_delay_get_state_f32
#define sms_delay_check_state sms_delay_check_state_f32
#define sms_delay_set_state sms_delay_set_state_f32
/* multi_generator.h */
#define sms_multi_generator_lag sms_multi_generator_lag_f32
/* scheduled.h */
#define sms_scheduled_buffer_size sms_scheduled_buffer_size_f32
#define sms_scheduled_init sms_scheduled_init_f32
#define sms_scheduled_reset sms_scheduled_reset_f32
#define sms_scheduled_step sms_scheduled_step_f32
#define sms_scheduled_process sms_scheduled_process_f32
#define sms_scheduled_mode sms_scheduled_mode_f32
#define sms_scheduled_taps sms_scheduled_taps_f32
#define sms_scheduled_lag sms_scheduled_lag_f32
#define sms_scheduled_state_count sms_scheduled_state_count_f32
#define sms_scheduled_get_state sms_scheduled_get_state_f32
#define sms_scheduled_set_state sms_scheduled_set_state_f32
/* tunable.h */
#define sms_tunable_active sms_tunable_active_f32
#define sms_tunable_chain_get_state sms_tunable_chain_get_state_f32
#define sms_tunable_chain_hold sms_tunable_chain_hold_f32
#define sms_tunable_chain_init sms_tunable_chain_init_f32
#define sms_tunable_chain_input_max sms_tunable_chain_input_max_f32
#define sms_tunable_chain_length sms_tunable_chain_length_f32
#define sms_tunable_chain_memory_size sms_tunable_chain_memory_size_f32
#define sms_tunable_chain_process sms_tunable_chain_process_f32
#define sms_tunable_chain_rebind sms_tunable_chain_rebind_f32
#define sms_tunable_chain_reset sms_tunable_chain_reset_f32
#define sms_tunable_chain_retune sms_tunable_chain_retune_f32
#define sms_tunable_chain_set_state sms_tunable_chain_set_state_f32
#define sms_tunable_chain_state_count sms_tunable_chain_state_count_f32
#define sms_tunable_chain_step sms_tunable_chain_step_f32
#define sms_tunable_chain_switching sms_tunable_chain_switching_f32
#define sms_tunable_check_state sms_tunable_check_state_f32
#define sms_tunable_check_state_range sms_tunable_check_state_range_f32
#define sms_tunable_config sms_tunable_config_f32
#define sms_tunable_gain_bound sms_tunable_gain_bound_f32
#define sms_tunable_get_state sms_tunable_get_state_f32
#define sms_tunable_init sms_tunable_init_f32
#define sms_tunable_input_max sms_tunable_input_max_f32
#define sms_tunable_memory_size sms_tunable_memory_size_f32
#define sms_tunable_process sms_tunable_process_f32
#define sms_tunable_rebind sms_tunable_rebind_f32
#define sms_tunable_reset sms_tunable_reset_f32
#define sms_tunable_retune sms_tunable_retune_f32
#define sms_tunable_set_state sms_tunable_set_state_f32
#define sms_tunable_slot_cells sms_tunable_slot_cells_f32
#define sms_tunable_switching sms_tunable_switching_f32
#define sms_tunable_switch_left sms_tunable_switch_left_f32
#define sms_tunable_step sms_tunable_step_f32
#define sms_tunable_state_count sms_tunable_state_count_f32
#define sms_tunable_state_configs sms_tunable_state_configs_f32
#endif

#endif
