(define (domain generator-torricelli-val)
  (:requirements :typing :fluents :time :negative-preconditions)
  (:types generator tank)
  (:predicates (idle ?g - generator) (generating ?g - generator) (generator-ran)
               (spilled ?g - generator) (busy ?g - generator)
               (refueling ?g - generator ?t - tank) (available ?t - tank))
  (:functions (fuel ?g - generator) (capacity ?g - generator) (tank-root ?t - tank)
              (gen-time ?g - generator) (gen-duration) (flow ?t - tank) (reserve-root))
  (:action start-generator
    :parameters (?g - generator)
    :precondition (and (idle ?g))
    :effect (and (not (idle ?g)) (generating ?g)))
  (:process generate
    :parameters (?g - generator)
    :precondition (and (generating ?g))
    :effect (and (decrease (fuel ?g) (* #t 1))
                 (increase (gen-time ?g) (* #t 1))))
  (:event generator-fails
    :parameters (?g - generator)
    :precondition (and (generating ?g) (< (fuel ?g) 0))
    :effect (and (not (generating ?g))))
  (:action stop-generator
    :parameters (?g - generator)
    :precondition (and (generating ?g) (not (spilled ?g)) (>= (gen-time ?g) (gen-duration)))
    :effect (and (not (generating ?g)) (generator-ran)))
  (:action start-refuel
    :parameters (?g - generator ?t - tank)
    :precondition (and (available ?t) (not (busy ?g)))
    :effect (and (not (available ?t)) (busy ?g) (refueling ?g ?t)))
  (:action stop-refuel
    :parameters (?g - generator ?t - tank)
    :precondition (and (refueling ?g ?t))
    :effect (and (not (refueling ?g ?t)) (not (busy ?g)) (available ?t)))
  ;; VAL twin: tank-root = sqrt(level) falls at flow/2; outflow flow * tank-root
  (:process refuel
    :parameters (?g - generator ?t - tank)
    :precondition (and (refueling ?g ?t))
    :effect (and (increase (fuel ?g) (* #t (* (flow ?t) (tank-root ?t))))
                 (decrease (tank-root ?t) (* #t (* 0.5 (flow ?t))))))
  (:event tank-empty
    :parameters (?g - generator ?t - tank)
    :precondition (and (refueling ?g ?t) (<= (tank-root ?t) (reserve-root)))
    :effect (and (not (refueling ?g ?t)) (not (busy ?g))))
  (:event overflow
    :parameters (?g - generator)
    :precondition (and (not (spilled ?g)) (> (fuel ?g) (capacity ?g)))
    :effect (and (spilled ?g)))
)
