(define (domain generator)
  (:requirements :typing :fluents :durative-actions :duration-inequalities :continuous-effects
                 :negative-preconditions)
  (:types generator tank)
  (:predicates (generator-ran) (refueling ?g - generator) (available ?t - tank))
  (:functions (fuel ?g - generator) (capacity ?g - generator) (tank-fuel ?t - tank)
              (gen-duration) (refuel-rate))
  ;; the generator runs for a fixed time, burning 1 unit/s; it may never run dry
  (:durative-action generate
    :parameters (?g - generator)
    :duration (= ?duration (gen-duration))
    :condition (and (over all (>= (fuel ?g) 0)))
    :effect (and (decrease (fuel ?g) (* #t 1))
                 (at end (generator-ran))))
  ;; pour (part of) a tank: at most until it is empty, never above capacity, one at a time
  (:durative-action refuel
    :parameters (?g - generator ?t - tank)
    :duration (and (>= ?duration 0) (<= ?duration (/ (tank-fuel ?t) (refuel-rate))))
    :condition (and (at start (not (refueling ?g))) (at start (available ?t))
                    (over all (<= (fuel ?g) (capacity ?g)))
                    (over all (>= (tank-fuel ?t) 0)))
    :effect (and (at start (refueling ?g)) (at start (not (available ?t)))
                 (at end (not (refueling ?g))) (at end (available ?t))
                 (increase (fuel ?g) (* #t (refuel-rate)))
                 (decrease (tank-fuel ?t) (* #t (refuel-rate)))))
)
